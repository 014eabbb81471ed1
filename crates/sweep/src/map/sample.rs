//! A fixed random sample of a map's points or runs: the same sample for the same map and
//! seed, on any machine (`droplet audit --sample`, `droplet bench --map --sample`).
use sha2::{Digest, Sha256};

/// `points` items (points or runs) drawn by `seed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub points: usize,
    pub seed: u64,
}

impl Sample {
    /// The `points` of `all` with the smallest SHA-256 of `(seed, id)`, `id` an item's bytes,
    /// in the order of those hashes.
    pub fn draw_by<T>(&self, all: impl Iterator<Item = T>, id: impl Fn(&T) -> Vec<u8>) -> Vec<T> {
        let mut ranked: Vec<([u8; 32], T)> = all
            .map(|item| {
                let mut h = Sha256::new();
                h.update(self.seed.to_le_bytes());
                h.update(id(&item));
                (h.finalize().into(), item)
            })
            .collect();
        ranked.sort_by_key(|r| r.0);
        ranked
            .into_iter()
            .take(self.points)
            .map(|(_, item)| item)
            .collect()
    }

    /// The `points` of the point numbers `all` ([`Self::draw_by`] on their bytes).
    pub fn draw(&self, all: impl Iterator<Item = u32>) -> std::collections::BTreeSet<u32> {
        self.draw_by(all, |p| p.to_le_bytes().to_vec())
            .into_iter()
            .collect()
    }
}

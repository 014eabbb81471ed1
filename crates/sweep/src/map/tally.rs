//! Counts of labels (statuses, classes), in a stable order.
use std::collections::BTreeMap;

/// Counts of each label.
pub fn tally(labels: impl IntoIterator<Item = String>) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    for l in labels {
        *out.entry(l).or_default() += 1;
    }
    out
}

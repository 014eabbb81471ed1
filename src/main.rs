//! `droplet`: phase diagrams of a self-propelled deformable droplet (Kitahata et al.).
//! A thin front end over `droplet-solver` and `droplet-sweep`; one file per subcommand.
mod cli;

fn main() {
    std::process::exit(cli::main());
}

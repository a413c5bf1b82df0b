//! The command-line program (placeholder until the CLI issue lands).
fn main() {
    eprintln!("triangle-rs: the command-line program is not built yet");
    std::process::exit(2);
}

//! The `bouncemap` binary; everything is in the library crate's [`bouncemap::main`].

fn main() -> std::process::ExitCode {
    bouncemap::main()
}

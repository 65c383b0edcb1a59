//! The `contopt` command: [`contopt_cli::main`] with the library's kinds.

fn main() -> std::process::ExitCode {
    contopt_cli::main()
}

//! `contopt-own`: the `contopt` command, every command kept, over the library's kinds and this
//! crate's ([`contopt_own_kinds::registry`]).

fn main() -> std::process::ExitCode {
    contopt_cli::main_with(contopt_own_kinds::registry())
}

//! `thirdbody`: the command line of the thirdbody contact solver (see
//! [`thirdbody_cli::app`]).

fn main() -> std::process::ExitCode {
    thirdbody_cli::app::main(std::env::args_os())
}

fn main() -> std::process::ExitCode {
    dicesim::cli::main()
}

fn main() -> std::process::ExitCode {
    turntable::cli::main()
}

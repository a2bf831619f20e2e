fn main() {
    std::process::exit(thud::cli::main());
}

fn main() {
    thud::signals::exit(thud::cli::main());
}

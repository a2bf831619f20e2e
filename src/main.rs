use clap::Parser;

fn main() {
    let cli = thud::cli::Cli::parse();
    std::process::exit(thud::cli::run(cli));
}

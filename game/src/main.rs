//! `headlamp`: play (default), render headless, bench, record, replay, script a replay, or check a level. Errors end the program with one line.

use std::process::ExitCode;

use clap::Parser;
use game::cli::{Cli, Command, PlayArgs};

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version
            print!("{e}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            let rendered = e.to_string();
            let first = rendered.lines().next().unwrap_or("error: bad arguments");
            eprintln!("{first} (see 'headlamp --help')");
            return ExitCode::from(2);
        }
    };
    let result = match cli.command.unwrap_or(Command::Play(PlayArgs::default())) {
        Command::Check(args) => return game::check::run(&args),
        Command::Play(args) => {
            let start = if args.level.is_some() { game::play::Start::InLevel } else { game::play::Start::MainMenu };
            game::play::run(&args.level.clone().unwrap_or_else(game::default_level), &args.levels_dirs, start)
        }
        Command::Render(args) => game::render_cmd::run(&args),
        Command::Bench(args) => game::bench::run(&args),
        Command::Record(args) => game::replay_cmd::record(&args),
        Command::Replay(args) => game::replay_cmd::replay(&args),
        Command::Script(args) => game::replay_cmd::script(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
            ExitCode::FAILURE
        }
    }
}

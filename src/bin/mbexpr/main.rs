//! The `mbexpr` command: a thin layer over the library.

mod binding;
mod check_cmd;
mod eval_cmd;
mod model_eval;
mod plot;
mod render;
mod repl;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Read, check and evaluate the function expressions of multibody models.
#[derive(Parser)]
#[command(name = "mbexpr", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the syntax tree of an expression as an S-expression.
    Parse {
        /// The expression, e.g. "STEP(TIME, 0, 0, 1, 10)".
        expression: String,
    },
    /// Check files of expressions, one per line (`!` starts a comment line; `-` is standard input).
    Check(check_cmd::Args),
    /// Evaluate an expression, with its derivatives on request.
    Eval(eval_cmd::Args),
    /// Plot an expression against one variable to an SVG file.
    Plot(plot::Args),
    /// Evaluate expressions interactively (or line by line from a pipe).
    Repl(repl::Args),
}

/// How a run ended, as the process's exit status.
pub enum Outcome {
    /// Everything was fine: 0.
    Success,
    /// The input had errors, which were reported: 1.
    Failure,
}

/// An error that ends the run: the message for standard error and the status.
pub struct Fatal {
    message: String,
    code: u8,
}

impl Fatal {
    /// A problem with how mbexpr was called (exit status 2).
    pub fn usage(message: impl Into<String>) -> Fatal {
        Fatal {
            message: message.into(),
            code: 2,
        }
    }

    /// A problem with the input, already explained in `message` (exit status 1).
    pub fn input(message: impl Into<String>) -> Fatal {
        Fatal {
            message: message.into(),
            code: 1,
        }
    }
}

impl Fatal {
    /// Whether the error is in the input (exit status 1) rather than the call.
    pub fn is_input(&self) -> bool {
        self.code == 1
    }

    /// The message for standard error.
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl From<io::Error> for Fatal {
    fn from(error: io::Error) -> Fatal {
        Fatal {
            message: format!("error: {error}"),
            code: if error.kind() == io::ErrorKind::BrokenPipe {
                0
            } else {
                2
            },
        }
    }
}

fn run(cli: Cli) -> Result<Outcome, Fatal> {
    let stdout = io::stdout();
    let mut out = io::BufWriter::new(stdout.lock());
    let outcome = match cli.command {
        Command::Parse { expression } => match mbexpr::parse(&expression) {
            Ok(tree) => {
                writeln!(out, "{tree}")?;
                Outcome::Success
            }
            Err(error) => {
                let text = render::diagnostic("", &expression, error.span(), &error.to_string());
                return Err(Fatal::input(text));
            }
        },
        Command::Check(args) => check_cmd::run(&args, &mut out)?,
        Command::Eval(args) => eval_cmd::run(&args, &mut out)?,
        Command::Plot(args) => plot::run(&args, &mut out)?,
        Command::Repl(args) => repl::run(&args, &mut out)?,
    };
    out.flush()?;
    Ok(outcome)
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => {
            let _ = error.print();
            return ExitCode::from(if error.use_stderr() { 2 } else { 0 });
        }
    };
    match run(cli) {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::Failure) => ExitCode::from(1),
        // A closed pipe (`mbexpr ... | head`) ends the run quietly.
        Err(fatal) if fatal.code == 0 => ExitCode::SUCCESS,
        Err(fatal) => {
            let _ = write!(io::stderr(), "{}", fatal.message);
            if !fatal.message.ends_with('\n') {
                let _ = writeln!(io::stderr());
            }
            ExitCode::from(fatal.code)
        }
    }
}

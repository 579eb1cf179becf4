//! The `mbexpr` command: a thin layer over the library.

mod check;
mod eval;
mod plot;
mod repl;
mod simulate;
mod support;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand};

/// mimalloc keeps the memory a run frees for its next use, where glibc's
/// allocator hands large blocks back to the system and faults them in
/// again (BENCHMARKS.md, "The allocator").
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

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
        #[arg(allow_hyphen_values = true)]
        expression: String,
    },
    /// Check files of expressions, one per line (`!` starts a comment line; `-` is standard input).
    Check(check::Args),
    /// Evaluate an expression, with its derivatives on request.
    Eval(eval::Args),
    /// Plot an expression against one variable to an SVG file.
    Plot(plot::Args),
    /// Evaluate expressions interactively (or line by line from a pipe).
    Repl(repl::Args),
    /// Print the completion script of a shell (`mbexpr completions bash > /etc/bash_completion.d/mbexpr`).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print the manual page of mbexpr or of one of its commands (`mbexpr man eval | man -l -`).
    Man {
        /// The command: parse, check, eval, plot, repl, simulate or completions; none for mbexpr itself.
        command: Option<String>,
    },
    /// Integrate a model's DIFF equations and free parts in time.
    Simulate(simulate::Args),
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
    /// A run ended early by signal number `signal`, its results so far
    /// written and reported: exit status 128 + the signal, as a shell
    /// gives it.
    pub fn signalled(signal: u8) -> Fatal {
        Fatal {
            message: String::new(),
            code: 128u8.saturating_add(signal),
        }
    }

    /// Whether the error is in the input (exit status 1) rather than the call.
    pub fn is_input(&self) -> bool {
        self.code == 1
    }

    /// The message for standard error.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// Whether there is something to tell (not a closed pipe, nor an
    /// error already reported).
    pub fn is_reportable(&self) -> bool {
        self.code != 0 && !self.message.is_empty()
    }

    /// The same exit status, the message already reported.
    pub fn reported(self) -> Fatal {
        Fatal {
            message: String::new(),
            code: self.code,
        }
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
                let text =
                    support::render::diagnostic("", &expression, error.span(), &error.to_string());
                return Err(Fatal::input(text));
            }
        },
        Command::Check(args) => check::run(&args, &mut out)?,
        Command::Eval(args) => eval::run(&args, &mut out)?,
        Command::Plot(args) => plot::run(&args, &mut out)?,
        Command::Repl(args) => repl::run(&args, &mut out)?,
        Command::Completions { shell } => {
            // clap_complete panics when its writer fails: it writes to
            // memory, and a closed pipe is met here, as an error.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "mbexpr", &mut script);
            out.write_all(&script)?;
            Outcome::Success
        }
        Command::Man { command } => {
            manual_page(command.as_deref())?.render(&mut out)?;
            Outcome::Success
        }
        Command::Simulate(args) => simulate::run(&args, &mut out)?,
    };
    out.flush()?;
    Ok(outcome)
}

/// The manual page of mbexpr, or of its command `command` (`mbexpr-eval(1)`).
fn manual_page(command: Option<&str>) -> Result<clap_mangen::Man, Fatal> {
    let mut cli = Cli::command();
    // Building names each command `mbexpr-NAME` for its page's title.
    cli.build();
    let page = match command {
        None => cli,
        Some(name) => cli.find_subcommand(name).cloned().ok_or_else(|| {
            let names: Vec<&str> = cli.get_subcommands().map(clap::Command::get_name).collect();
            Fatal::usage(format!(
                "error: mbexpr has no command {name}: name one of {}",
                names.join(", ")
            ))
        })?,
    };
    Ok(clap_mangen::Man::new(page))
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
        Err(fatal) if fatal.message.is_empty() => ExitCode::from(fatal.code),
        Err(fatal) => {
            let _ = write!(io::stderr(), "{}", fatal.message);
            if !fatal.message.ends_with('\n') {
                let _ = writeln!(io::stderr());
            }
            ExitCode::from(fatal.code)
        }
    }
}

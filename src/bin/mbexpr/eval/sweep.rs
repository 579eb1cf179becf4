//! `eval --points`: one program at every row of a points file, as a
//! stream. Rows are read in batches; while one batch is read, the one
//! before is evaluated in chunks on every core (rayon), and the results are
//! written in the order of the rows, so memory does not grow with the file.

use std::io::Write;

use csv::ByteRecord;
use mbexpr::{Evaluation, Order, Program, Run};
use rayon::prelude::*;

use super::Format;
use crate::Fatal;
use crate::support::points::{Batch, PointsFile, line_of, read_values};
use crate::support::record::{Problem, Record};
use crate::support::values::push_aligned;

/// Rows a core takes at a time.
const CHUNK: usize = 256;

/// Width of a number column of the text table: the longest shortest
/// round-trip text of a double, `-1.2345678901234567e-300`.
const NUMBER_WIDTH: usize = 24;

/// One program and how to evaluate and print it at each row.
pub struct Sweep<'a> {
    /// The program.
    pub program: &'a Program,
    /// The expression's text, for the place of an evaluation error.
    pub source: &'a str,
    /// The value of every input before a row gives its columns.
    pub base: &'a [f64],
    /// The names of the file's columns.
    pub names: &'a [String],
    /// `(column, input)`: the columns the program reads, and where.
    pub columns: &'a [(usize, usize)],
    /// The derivative directions, as inputs and as names.
    pub wrt: &'a [usize],
    /// Their names.
    pub wrt_names: &'a [String],
    /// How many derivatives.
    pub order: Order,
    /// The output format.
    pub format: Format,
    /// The expression's name, for jsonl.
    pub name: Option<&'a str>,
    /// Put before each line of a JSON document (inside a named one).
    pub indent: &'a str,
}

/// What a chunk of rows gave: its text, in row order, and its failed rows.
#[derive(Default)]
struct Output {
    text: Vec<u8>,
    failures: usize,
}

impl Sweep<'_> {
    /// Evaluates every row of `file`, writing each result in row order;
    /// returns how many rows failed.
    pub fn run(&self, file: &mut PointsFile, out: &mut impl Write) -> Result<usize, Fatal> {
        match self.format {
            Format::Text => writeln!(out, "{}", self.table_header())?,
            Format::Json => write!(out, "[")?,
            Format::Jsonl => {}
        }
        // A program with AX, AY or AZ continues them from row to row: its
        // rows go in order, on one core.
        let mut run = self
            .program
            .continues_from_point_to_point()
            .then(|| self.program.run());
        let (mut current, mut next) = (Batch::default(), Batch::default());
        file.read_batch(&mut current)?;
        let (mut failures, mut first) = (0, true);
        while !current.rows().is_empty() {
            let (read, outputs) = rayon::join(
                || file.read_batch(&mut next),
                || self.evaluate(current.rows(), run.as_mut()),
            );
            for output in outputs {
                let mut text = &output.text[..];
                if first && self.format == Format::Json && !text.is_empty() {
                    // The comma before the first row of the document.
                    text = &text[1..];
                    first = false;
                }
                out.write_all(text)?;
                failures += output.failures;
            }
            read?;
            std::mem::swap(&mut current, &mut next);
        }
        if self.format == Format::Json {
            write!(out, "\n{}]", self.indent)?;
        }
        Ok(failures)
    }

    /// The results of `rows`: in chunks on every core, each chunk a run of
    /// its own, or all through `run`, in order, when there is one.
    fn evaluate(&self, rows: &[ByteRecord], run: Option<&mut Run<'_>>) -> Vec<Output> {
        match run {
            Some(run) => vec![self.evaluate_rows(rows, run)],
            None => rows
                .par_chunks(CHUNK)
                .map(|rows| self.evaluate_rows(rows, &mut self.program.run()))
                .collect(),
        }
    }

    fn evaluate_rows(&self, rows: &[ByteRecord], run: &mut Run<'_>) -> Output {
        let mut output = Output::default();
        let mut point = self.base.to_vec();
        run.with_evaluator(self.wrt, self.order, |evaluate| {
            for row in rows {
                let result = read_values(row, self.names, self.columns, &mut point)
                    .map_err(Problem::plain)
                    .and_then(|()| {
                        evaluate(&point)
                            .map_err(|error| Problem::at(self.source, error.span(), &error))
                    });
                if result.is_err() {
                    output.failures += 1;
                }
                let result = result.as_ref().map_err(std::slice::from_ref);
                self.write_row(&mut output.text, line_of(row), result);
            }
        });
        output
    }

    /// One row's result as its format writes it.
    fn write_row(&self, text: &mut Vec<u8>, line: u64, result: Result<&Evaluation, &[Problem]>) {
        let record = Record {
            name: self.name,
            row: Some(line),
            wrt: self.wrt_names,
            result,
        };
        match self.format {
            Format::Text => {
                let _ = write!(text, "{line:<8}");
                match result {
                    Ok(evaluation) => {
                        for value in numbers(evaluation) {
                            text.push(b' ');
                            push_aligned(text, value, NUMBER_WIDTH);
                        }
                    }
                    Err(problems) => {
                        text.push(b' ');
                        text.extend_from_slice(problems[0].headline().as_bytes());
                    }
                }
                text.push(b'\n');
            }
            Format::Json => {
                let record = Record {
                    name: None,
                    ..record
                };
                let _ = write!(text, ",\n{}  ", self.indent);
                serde_json::to_writer(&mut *text, &record).expect("a record serializes");
            }
            Format::Jsonl => {
                serde_json::to_writer(&mut *text, &record).expect("a record serializes");
                text.push(b'\n');
            }
        }
    }

    /// `row  value  d/dx  d/dv  d2/dx,dx  d2/dx,dv  d2/dv,dv`: the columns of
    /// the text table (the Hessian's upper triangle, row by row).
    fn table_header(&self) -> String {
        let mut titles = vec!["value".to_string()];
        if self.order >= Order::Gradient {
            titles.extend(self.wrt_names.iter().map(|name| format!("d/d{name}")));
        }
        if self.order >= Order::Hessian {
            for (index, first) in self.wrt_names.iter().enumerate() {
                for second in &self.wrt_names[index..] {
                    titles.push(format!("d2/d{first},d{second}"));
                }
            }
        }
        let mut header = format!("{:<8}", "row");
        for title in titles {
            header += &format!(" {title:>NUMBER_WIDTH$}");
        }
        header
    }
}

/// The value, the gradient and the Hessian's upper triangle, row by row.
fn numbers(evaluation: &Evaluation) -> impl Iterator<Item = f64> + '_ {
    let gradient = evaluation.gradient.iter().flatten().copied();
    let hessian = evaluation.hessian.iter().flat_map(|hessian| {
        (0..hessian.nrows())
            .flat_map(move |row| (row..hessian.ncols()).map(move |column| hessian[(row, column)]))
    });
    std::iter::once(evaluation.value)
        .chain(gradient)
        .chain(hessian)
}

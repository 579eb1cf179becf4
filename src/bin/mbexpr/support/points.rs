//! `eval --points FILE.csv`: the header and the rows of a CSV file of
//! points, read as a stream in batches, each row with its line in the file.
//!
//! The `csv` crate reads the file (quoted fields, a UTF-8 byte order mark,
//! `\n`, `\r\n` and `\r` line endings); blank lines and lines starting with
//! `#` are skipped but still counted, so a row is known by its line. The
//! separator is the first of `,` `;` and tab that the header holds. Blanks
//! around a name or a number are not part of it (trimmed where read, not
//! by the reader, which would allocate each record anew).

use std::collections::{HashMap, VecDeque};
use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};

use csv::{ByteRecord, ReaderBuilder};

use crate::Fatal;

/// Rows read at a time: enough to keep every core busy, little memory.
const BATCH: usize = 4096;

/// The bytes of a batch beyond which it takes no more rows (rows of
/// thousands of columns).
const BATCH_BYTES: usize = 1 << 20;

/// The names a header may show in a message before it says how many more.
const NAMES_SHOWN: usize = 8;

/// An open file of points: its header, and the rows still to read.
pub struct PointsFile {
    /// The path as given (`-` for standard input), for messages.
    pub path: String,
    /// The line of the header row.
    pub header_line: u64,
    /// The column names, trimmed, without the empty names a trailing
    /// separator leaves.
    pub names: Vec<String>,
    reader: csv::Reader<Lines<Box<dyn BufRead + Send>>>,
}

/// Rows read from a file, reused from batch to batch.
#[derive(Default)]
pub struct Batch {
    records: Vec<ByteRecord>,
    len: usize,
}

impl Batch {
    /// The rows of the last read.
    pub fn rows(&self) -> &[ByteRecord] {
        &self.records[..self.len]
    }
}

impl PointsFile {
    /// Opens `path` (`-`: standard input) and reads its header.
    pub fn open(path: &str) -> Result<PointsFile, Fatal> {
        let cannot_read =
            |error: io::Error| Fatal::usage(format!("error: cannot read {path}: {error}"));
        let input: Box<dyn Read + Send> = if path == "-" {
            Box::new(io::stdin())
        } else {
            Box::new(File::open(path).map_err(cannot_read)?)
        };
        let mut input: Box<dyn BufRead + Send> = Box::new(BufReader::with_capacity(1 << 16, input));
        let separator = separator_of(input.fill_buf().map_err(cannot_read)?);
        let mut reader = ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .comment(Some(b'#'))
            .delimiter(separator)
            .from_reader(Lines::new(input));
        let mut header = ByteRecord::new();
        let header_line = loop {
            if !read_row(&mut reader, &mut header).map_err(|error| cannot_read(error.into()))? {
                return Err(Fatal::usage(format!(
                    "error: {path} has no header: its first row must name the variables, such as x,v"
                )));
            }
            if !is_blank(&header) {
                break line_of(&header);
            }
        };
        let names = header_names(&header)
            .map_err(|message| Fatal::usage(format!("error: {path}:{header_line}: {message}")))?;
        Ok(PointsFile {
            path: path.to_string(),
            header_line,
            names,
            reader,
        })
    }

    /// Reads up to [`BATCH`] rows (or a megabyte) into `batch`, skipping
    /// blank ones; an empty batch is the end of the file.
    pub fn read_batch(&mut self, batch: &mut Batch) -> Result<(), Fatal> {
        batch.records.resize_with(BATCH, ByteRecord::new);
        batch.len = 0;
        let mut bytes = 0;
        while batch.len < BATCH && bytes < BATCH_BYTES {
            let record = &mut batch.records[batch.len];
            let more = read_row(&mut self.reader, record).map_err(|error| {
                Fatal::usage(format!("error: cannot read {}: {error}", self.path))
            })?;
            if !more {
                break;
            }
            if !is_blank(record) {
                bytes += record.as_slice().len();
                batch.len += 1;
            }
        }
        Ok(())
    }
}

/// Names in a message: `x, v`, the first few of many and how many more.
pub fn some_names<S: AsRef<str>>(names: &[S]) -> String {
    let shown: Vec<&str> = names.iter().take(NAMES_SHOWN).map(AsRef::as_ref).collect();
    let mut text = shown.join(", ");
    if names.len() > NAMES_SHOWN {
        text += &format!(" and {} more", names.len() - NAMES_SHOWN);
    }
    text
}

/// The line a row starts on.
pub fn line_of(record: &ByteRecord) -> u64 {
    record.position().map_or(0, csv::Position::line)
}

/// Reads the next record, with its line in the file; `false` at the end.
/// A record's own position is where the reader stood before it, blank and
/// comment lines included; the line of its last byte is its line (the
/// last, for a quoted field over several lines).
fn read_row<R: BufRead>(
    reader: &mut csv::Reader<Lines<R>>,
    record: &mut ByteRecord,
) -> csv::Result<bool> {
    if !reader.read_byte_record(record)? {
        return Ok(false);
    }
    let end = reader.position().byte().saturating_sub(1);
    let line = reader.get_mut().line_at(end);
    let mut position = record
        .position()
        .cloned()
        .unwrap_or_else(csv::Position::new);
    position.set_line(line);
    record.set_position(Some(position));
    Ok(true)
}

/// Whether every field of a row is blank (a line of blanks or separators).
fn is_blank(record: &ByteRecord) -> bool {
    record.iter().all(|cell| cell.trim_ascii().is_empty())
}

/// The separator of a file: the first of `,` `;` and tab that its first
/// line that is not a comment holds; `,` when it holds none (one column).
fn separator_of(start: &[u8]) -> u8 {
    let header = start
        .split(|&byte| byte == b'\n' || byte == b'\r')
        .find(|line| !line.trim_ascii().is_empty() && !line.starts_with(b"#"))
        .unwrap_or_default();
    [b',', b';', b'\t']
        .into_iter()
        .find(|separator| header.contains(separator))
        .unwrap_or(b',')
}

/// The names of a header row: trimmed, each a name, none twice (names are
/// case-insensitive), the empty names a trailing separator leaves dropped.
fn header_names(header: &ByteRecord) -> Result<Vec<String>, String> {
    let mut names: Vec<String> = header
        .iter()
        .map(|name| String::from_utf8_lossy(name.trim_ascii()).into_owned())
        .collect();
    while names.last().is_some_and(String::is_empty) {
        names.pop();
    }
    let mut seen: HashMap<String, usize> = HashMap::with_capacity(names.len());
    for (index, name) in names.iter().enumerate() {
        let column = index + 1;
        if name.is_empty() {
            return Err(format!("column {column} of the header has no name"));
        }
        if name.parse::<f64>().is_ok() {
            return Err(format!(
                "the first row must name the variables, but column {column} is the number {name}: add a header such as x,v (a line that starts with # is a comment)"
            ));
        }
        if let Some(first) = seen.insert(name.to_ascii_lowercase(), column) {
            return Err(format!(
                "columns {first} and {column} are both named {name}: name each variable once"
            ));
        }
    }
    Ok(names)
}

/// Reads the values of the columns a program uses from `row` into `point`:
/// `columns` pairs a column with the input it gives.
pub fn read_values(
    row: &ByteRecord,
    names: &[String],
    columns: &[(usize, usize)],
    point: &mut [f64],
) -> Result<(), String> {
    // Empty cells past the last column are what a trailing separator leaves.
    let extra = row
        .iter()
        .skip(names.len())
        .any(|cell| !cell.trim_ascii().is_empty());
    if row.len() < names.len() || extra {
        return Err(format!(
            "the row has {} for {}",
            mbexpr::Counted(row.len(), "value"),
            mbexpr::Counted(names.len(), "column")
        ));
    }
    for &(column, input) in columns {
        let cell = row[column].trim_ascii();
        point[input] = std::str::from_utf8(cell)
            .ok()
            .and_then(|text| text.parse::<f64>().ok())
            .filter(|value| value.is_finite())
            .ok_or_else(|| {
                format!(
                    "{}: `{}` is not a finite number",
                    names[column],
                    String::from_utf8_lossy(cell)
                )
            })?;
    }
    Ok(())
}

/// The reader under the CSV reader: it turns a lone `\r` (the line end of
/// old Mac files) into `\n`, leaving `\r\n` as it is and every offset where
/// it was, and it keeps where lines start, so that a row is known by its
/// line in the file whatever its line ends (the CSV reader's own count
/// skips blank lines and `\r\n`).
struct Lines<R> {
    inner: R,
    /// The bytes passed on so far.
    offset: u64,
    /// Where the lines after line `line` start, up to `offset`.
    starts: VecDeque<u64>,
    /// The line of the last byte asked about, from 1.
    line: u64,
}

impl<R> Lines<R> {
    fn new(inner: R) -> Lines<R> {
        Lines {
            inner,
            offset: 0,
            starts: VecDeque::new(),
            line: 1,
        }
    }

    /// The line of byte `offset`, for offsets asked about in increasing order.
    fn line_at(&mut self, offset: u64) -> u64 {
        while self.starts.front().is_some_and(|&start| start <= offset) {
            self.starts.pop_front();
            self.line += 1;
        }
        self.line
    }
}

impl<R: BufRead> Read for Lines<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let buffer = self.inner.fill_buf()?;
        let count = buffer.len().min(out.len());
        out[..count].copy_from_slice(&buffer[..count]);
        for index in memchr::memchr_iter(b'\r', &buffer[..count]) {
            if buffer.get(index + 1).is_some_and(|&next| next != b'\n') {
                out[index] = b'\n';
            }
        }
        // A `\r` that ends the buffer is decided by the next buffer.
        let undecided = count > 0 && count == buffer.len() && buffer[count - 1] == b'\r';
        self.inner.consume(count);
        if undecided && self.inner.fill_buf()?.first() != Some(&b'\n') {
            out[count - 1] = b'\n';
        }
        let offset = self.offset;
        self.starts.extend(
            memchr::memchr_iter(b'\n', &out[..count]).map(|index| offset + index as u64 + 1),
        );
        self.offset += count as u64;
        Ok(count)
    }
}

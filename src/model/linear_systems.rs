//! The linear systems of a dataset's control elements, as `ARYVAL` reads
//! them: `TFSISO` (a transfer function of one input) and `LSE`
//! (`x' = A x + B u`, `y = C x + D u`, its matrices in `MATRIX`
//! statements). The states are entries of the X array, the inputs the
//! VARIABLEs of the U array, the outputs entries of the Y array.

use nalgebra::DMatrix;

use super::initial::{ConfigurationError, number_list};
use super::{Dataset, Statement, Value, is_statement};
use crate::Checked;
use crate::scene::{LinearSystem, array_state_input};

/// The most entries a MATRIX may have (each nonzero one is a term of an
/// equation; a hundred million zeros would fill the memory).
const MOST_ENTRIES: usize = 1_000_000;

/// The linear systems of `dataset`'s TFSISO and LSE statements, and what
/// is wrong with those that cannot be read.
pub(crate) fn linear_systems(dataset: &Dataset) -> (Vec<LinearSystem>, Vec<ConfigurationError>) {
    let mut systems = Vec::new();
    let mut errors = Vec::new();
    for statement in &dataset.statements {
        let read = if is_statement(statement, "TFSISO") {
            transfer_function(dataset, statement)
        } else if is_statement(statement, "LSE") {
            state_equations(dataset, statement)
        } else {
            continue;
        };
        match read.and_then(|system| arrays_unshared(statement, &system, &systems).map(|()| system))
        {
            Ok(system) => systems.push(system),
            Err(error) => errors.push(error),
        }
    }
    (systems, errors)
}

/// Refuses a system whose X or Y array an earlier one has: an array of
/// states or outputs belongs to one LSE, GSE or TFSISO (Adams' ARRAY
/// page), else one system's states would be read as another's.
fn arrays_unshared(
    statement: &Statement,
    system: &LinearSystem,
    earlier: &[LinearSystem],
) -> Result<(), ConfigurationError> {
    for other in earlier {
        let shared = if other.states == system.states {
            Some(("X", system.states))
        } else {
            system
                .outputs
                .filter(|&y| other.outputs == Some(y))
                .map(|y| ("Y", y))
        };
        if let Some((keyword, id)) = shared {
            return Err(refused(
                statement,
                format!(
                    "{keyword} = {id} is {}'s already: an ARRAY of states or outputs belongs to one LSE, GSE or TFSISO (give this one its own ARRAY)",
                    other.statement
                ),
            ));
        }
    }
    Ok(())
}

/// The error `statement: reason` at the statement.
fn refused(statement: &Statement, reason: String) -> ConfigurationError {
    ConfigurationError::Control {
        statement: statement.label(),
        reason,
        span: statement.span,
    }
}

/// The id a statement's `keyword = id` gives, `None` when it has none.
fn id_of(statement: &Statement, keyword: &str) -> Result<Option<u64>, ConfigurationError> {
    let Some(argument) = statement.argument(keyword, keyword.len()) else {
        return Ok(None);
    };
    match number_list(statement, argument)?.as_slice() {
        [id] if id.fract() == 0.0 && *id > 0.0 => Ok(Some(*id as u64)),
        _ => Err(refused(
            statement,
            format!("{keyword} must be the id of a statement"),
        )),
    }
}

/// The statement `kind/id` of the dataset.
pub(crate) fn find<'d>(dataset: &'d Dataset, kind: &str, id: u64) -> Option<&'d Statement> {
    dataset
        .statements
        .iter()
        .find(|statement| is_statement(statement, kind) && statement.id == Some(id))
}

/// The ARRAY that `keyword` of `statement` names, checked to be of `kind`
/// (X, U, Y or IC) and, where it gives its size, of `size` entries.
fn array<'d>(
    dataset: &'d Dataset,
    statement: &Statement,
    keyword: &str,
    kind: &str,
    size: usize,
) -> Result<Option<(u64, &'d Statement)>, ConfigurationError> {
    let Some(id) = id_of(statement, keyword)? else {
        return Ok(None);
    };
    let Some(array) = find(dataset, "ARRAY", id) else {
        return Err(refused(
            statement,
            format!("{keyword} = {id} names no ARRAY/{id}"),
        ));
    };
    let types = ["X", "U", "Y", "IC"];
    let written = types
        .into_iter()
        .find(|kind| array.argument(kind, kind.len()).is_some());
    if written.is_some_and(|written| written != kind) {
        return Err(refused(
            statement,
            format!("{keyword} = {id} must name an ARRAY of type {kind}"),
        ));
    }
    let count = match (kind, array.argument("SIZE", 2)) {
        ("U", _) => array
            .argument("VARIABLES", 3)
            .map(|argument| match &argument.value {
                Value::List(items) => items.len(),
                _ => 0,
            }),
        ("IC", _) => None,
        (_, Some(argument)) => number_list(array, argument)?.first().map(|n| *n as usize),
        (_, None) => None,
    };
    if let Some(count) = count.filter(|count| *count != size) {
        return Err(refused(
            statement,
            format!("ARRAY/{id} ({keyword}) has {count} entries, the system {size}"),
        ));
    }
    Ok(Some((id, array)))
}

/// The numbers of a statement's `keyword` list.
fn numbers(statement: &Statement, keyword: &str) -> Result<Vec<f64>, ConfigurationError> {
    match statement.argument(keyword, keyword.len().min(3)) {
        Some(argument) => number_list(statement, argument),
        None => Err(refused(statement, format!("needs {keyword}"))),
    }
}

/// `TFSISO`: `NUMERATOR` and `DENOMINATOR` in ascending powers of `s`,
/// realised in controllable canonical form: `x1' = x2`, ..., `xn' = u -
/// (a0 x1 + ... + a(n-1) xn) / an`, `y = (b'0 x1 + ... + b'(n-1) xn) / an +
/// (bn / an) u` with `b' = b - (bn / an) a` (the part of a proper
/// function that passes straight through).
fn transfer_function(
    dataset: &Dataset,
    statement: &Statement,
) -> Result<LinearSystem, ConfigurationError> {
    if statement.argument("IC", 2).is_some() {
        return Err(refused(
            statement,
            "IC is not read: the states of mbexpr's realisation of a transfer function (controllable canonical form) need not be those Adams chooses; start it at rest, or write the system as an LSE with its IC".to_string(),
        ));
    }
    let numerator = numbers(statement, "NUMERATOR")?;
    let denominator = numbers(statement, "DENOMINATOR")?;
    let order = denominator.len() - 1;
    let leading = denominator[order];
    if order == 0 || leading == 0.0 {
        return Err(refused(
            statement,
            "the DENOMINATOR's last coefficient (of the highest power of s, at least s^1) must not be zero".to_string(),
        ));
    }
    if numerator.len() > denominator.len() {
        return Err(refused(
            statement,
            format!(
                "the NUMERATOR is of degree {}, above the DENOMINATOR's {order}: the transfer function is not proper",
                numerator.len() - 1
            ),
        ));
    }
    let through = numerator.get(order).map_or(0.0, |b| b / leading);
    let mut a = DMatrix::zeros(order, order);
    for row in 0..order - 1 {
        a[(row, row + 1)] = 1.0;
    }
    for column in 0..order {
        a[(order - 1, column)] = -denominator[column] / leading;
    }
    let mut b = DMatrix::zeros(order, 1);
    b[(order - 1, 0)] = 1.0;
    let c = DMatrix::from_fn(1, order, |_, column| {
        (numerator.get(column).copied().unwrap_or(0.0) - through * denominator[column]) / leading
    });
    let d = DMatrix::from_element(1, 1, through);
    system(dataset, statement, [a, b, c, d], Vec::new())
}

/// `LSE`: the matrices `A` (required), `B`, `C`, `D` and the initial
/// states `IC` (an ARRAY of NUMBERS).
fn state_equations(
    dataset: &Dataset,
    statement: &Statement,
) -> Result<LinearSystem, ConfigurationError> {
    let matrix = |keyword: &str| -> Result<Option<DMatrix<f64>>, ConfigurationError> {
        let Some(id) = id_of(statement, keyword)? else {
            return Ok(None);
        };
        match find(dataset, "MATRIX", id) {
            Some(found) => read_matrix(found).map(Some),
            None => Err(refused(
                statement,
                format!("{keyword} = {id} names no MATRIX/{id}"),
            )),
        }
    };
    let Some(a) = matrix("A")? else {
        return Err(refused(statement, "needs A, its state matrix".to_string()));
    };
    let states = a.nrows();
    if a.ncols() != states {
        return Err(refused(
            statement,
            format!("A is {} by {}: it must be square", a.nrows(), a.ncols()),
        ));
    }
    let b = matrix("B")?;
    let c = matrix("C")?;
    let inputs = b.as_ref().map_or(0, DMatrix::ncols);
    let outputs = c.as_ref().map_or(0, DMatrix::nrows);
    let b = b.unwrap_or_else(|| DMatrix::zeros(states, 0));
    let c = c.unwrap_or_else(|| DMatrix::zeros(0, states));
    let d = matrix("D")?.unwrap_or_else(|| DMatrix::zeros(outputs, inputs));
    let shapes = [
        ("B", &b, states, inputs),
        ("C", &c, outputs, states),
        ("D", &d, outputs, inputs),
    ];
    for (keyword, matrix, rows, columns) in shapes {
        if (matrix.nrows(), matrix.ncols()) != (rows, columns) {
            return Err(refused(
                statement,
                format!(
                    "{keyword} is {} by {}, where A, B and C make it {rows} by {columns}",
                    matrix.nrows(),
                    matrix.ncols()
                ),
            ));
        }
    }
    let initial = match array(dataset, statement, "IC", "IC", states)? {
        Some((id, found)) => {
            let values = match found.argument("NUMBERS", 2) {
                Some(argument) => number_list(found, argument)?,
                None => Vec::new(),
            };
            if values.len() != states {
                return Err(refused(
                    statement,
                    format!(
                        "IC = {id}: ARRAY/{id} has {} numbers, the system {states} states",
                        values.len()
                    ),
                ));
            }
            values
        }
        None => Vec::new(),
    };
    system(dataset, statement, [a, b, c, d], initial)
}

/// A MATRIX statement's matrix: `FULL = RORDER` (by rows) or `CORDER` (by
/// columns, the default) with `ROWS`, `COLUMNS` and `VALUES`, or `SPARSE`
/// with `I`, `J` and `VALUES` (entries not given are zero).
pub(crate) fn read_matrix(statement: &Statement) -> Result<DMatrix<f64>, ConfigurationError> {
    if statement.argument("FILE", 4).is_some() {
        return Err(refused(
            statement,
            "a matrix read from a FILE is not read: give ROWS, COLUMNS and VALUES".to_string(),
        ));
    }
    let size = |keyword: &str| -> Result<usize, ConfigurationError> {
        match numbers(statement, keyword)?.as_slice() {
            [n] if n.fract() == 0.0 && *n >= 1.0 && *n <= 10_000.0 => Ok(*n as usize),
            _ => Err(refused(
                statement,
                format!("{keyword} must be a whole number from 1 to 10000"),
            )),
        }
    };
    let (rows, columns) = (size("ROWS")?, size("COLUMNS")?);
    if rows * columns > MOST_ENTRIES {
        return Err(refused(
            statement,
            format!(
                "{rows} by {columns} is more than the {MOST_ENTRIES} entries a MATRIX may have"
            ),
        ));
    }
    let values = numbers(statement, "VALUES")?;
    if statement.argument("SPARSE", 2).is_some() {
        let (row_ids, column_ids) = (numbers(statement, "I")?, numbers(statement, "J")?);
        if row_ids.len() != values.len() || column_ids.len() != values.len() {
            return Err(refused(
                statement,
                "a SPARSE matrix needs as many I and J as VALUES".to_string(),
            ));
        }
        let mut matrix = DMatrix::zeros(rows, columns);
        for ((row, column), value) in row_ids.iter().zip(&column_ids).zip(&values) {
            let within = |index: f64, count: usize| {
                (index.fract() == 0.0 && index >= 1.0 && index <= count as f64)
                    .then(|| index as usize - 1)
            };
            let (Some(row), Some(column)) = (within(*row, rows), within(*column, columns)) else {
                return Err(refused(
                    statement,
                    format!("entry ({row}, {column}) is outside its {rows} by {columns}"),
                ));
            };
            matrix[(row, column)] = *value;
        }
        return Ok(matrix);
    }
    if values.len() != rows * columns {
        return Err(refused(
            statement,
            format!("{} VALUES for {rows} by {columns} entries", values.len()),
        ));
    }
    let by_rows = match statement
        .argument("FULL", 2)
        .map(|argument| &argument.value)
    {
        Some(Value::List(items)) => items
            .first()
            .is_some_and(|item| item.text.trim().eq_ignore_ascii_case("RORDER")),
        _ => false,
    };
    Ok(if by_rows {
        DMatrix::from_row_slice(rows, columns, &values)
    } else {
        DMatrix::from_column_slice(rows, columns, &values)
    })
}

/// The system of `statement` with its matrices `[A, B, C, D]`, its arrays
/// checked against them, and the expressions of its states' rates and its
/// outputs in `ARYVAL` of its arrays.
fn system(
    dataset: &Dataset,
    statement: &Statement,
    [a, b, c, d]: [DMatrix<f64>; 4],
    initial: Vec<f64>,
) -> Result<LinearSystem, ConfigurationError> {
    let (states, inputs, outputs) = (a.nrows(), b.ncols(), c.nrows());
    let Some((x, _)) = array(dataset, statement, "X", "X", states)? else {
        return Err(refused(
            statement,
            "needs X, the ARRAY of its states".to_string(),
        ));
    };
    let u = array(dataset, statement, "U", "U", inputs)?.map(|(id, _)| id);
    let y = array(dataset, statement, "Y", "Y", outputs)?.map(|(id, _)| id);
    if u.is_none() && inputs > 0 {
        return Err(refused(
            statement,
            format!("needs U, the ARRAY of its {inputs} inputs"),
        ));
    }
    let input_names: Vec<String> = (1..=inputs)
        .map(|k| format!("ARYVAL({}, {k})", u.unwrap_or(0)))
        .collect();
    let state_names: Vec<String> = (1..=states).map(|k| array_state_input(x, k)).collect();
    let combination = |row: usize, left: &DMatrix<f64>, right: &DMatrix<f64>| {
        linear_text(
            state_names
                .iter()
                .enumerate()
                .map(|(k, name)| (left[(row, k)], name))
                .chain(
                    input_names
                        .iter()
                        .enumerate()
                        .map(|(k, name)| (right[(row, k)], name)),
                ),
        )
    };
    let checked = |text: String| -> Result<(String, Checked), ConfigurationError> {
        let tree = crate::parse(&text)
            .ok()
            .and_then(|tree| crate::check(&tree).ok())
            .ok_or_else(|| refused(statement, format!("cannot write its equation `{text}`")))?;
        Ok((text, tree))
    };
    let rates = (0..states)
        .map(|row| checked(combination(row, &a, &b)))
        .collect::<Result<_, _>>()?;
    let output_expressions = (0..outputs)
        .map(|row| checked(combination(row, &c, &d)))
        .collect::<Result<_, _>>()?;
    Ok(LinearSystem {
        statement: statement.label(),
        span: statement.span,
        states: x,
        inputs: u,
        outputs: y,
        initial: if initial.is_empty() {
            vec![0.0; states]
        } else {
            initial
        },
        rates,
        output_expressions,
        static_hold: statement.argument("STATIC_HOLD", 8).is_some(),
    })
}

/// `c1 * n1 + c2 * n2 + ...` over the nonzero coefficients, `0` when all
/// are zero; each coefficient written to round trip.
fn linear_text<'n>(terms: impl Iterator<Item = (f64, &'n String)>) -> String {
    let text: Vec<String> = terms
        .filter(|(coefficient, _)| *coefficient != 0.0)
        .map(|(coefficient, name)| format!("({coefficient:?}) * {name}"))
        .collect();
    if text.is_empty() {
        "0".to_string()
    } else {
        text.join(" + ")
    }
}

//! Values and derivatives of every function against the table computed with
//! mpmath (`tests/data/reference.tsv`, made by `scripts/reference_values.py`).

use mbexpr::Order;

/// One row of the table.
struct Row {
    expression: String,
    names: Vec<String>,
    values: Vec<f64>,
    wrt: Vec<String>,
    value: f64,
    gradient: Vec<f64>,
    hessian: Vec<Vec<f64>>,
    tolerance: f64,
}

fn numbers(text: &str) -> Vec<f64> {
    text.split(';')
        .filter(|entry| !entry.trim().is_empty())
        .map(|entry| {
            entry
                .trim()
                .parse()
                .unwrap_or_else(|_| panic!("`{entry}` is not a number"))
        })
        .collect()
}

fn rows() -> Vec<Row> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/reference.tsv");
    let text = std::fs::read_to_string(path).expect("the reference table is in the repository");
    text.lines()
        .filter(|line| {
            !line.starts_with('#') && !line.starts_with("expression\t") && !line.trim().is_empty()
        })
        .map(|line| {
            let columns: Vec<&str> = line.split('\t').collect();
            assert_eq!(columns.len(), 7, "{line}");
            let (names, values) = columns[1]
                .split(';')
                .filter(|pair| !pair.is_empty())
                .map(|pair| {
                    let (name, value) = pair.split_once('=').expect("name=value");
                    (name.to_string(), value.parse::<f64>().expect("a number"))
                })
                .unzip();
            Row {
                expression: columns[0].to_string(),
                names,
                values,
                wrt: columns[2]
                    .split(',')
                    .filter(|name| !name.is_empty())
                    .map(str::to_string)
                    .collect(),
                value: columns[3].parse().expect("a value"),
                gradient: numbers(columns[4]),
                hessian: columns[5]
                    .split('|')
                    .map(numbers)
                    .filter(|row| !row.is_empty())
                    .collect(),
                tolerance: columns[6].parse().expect("a tolerance"),
            }
        })
        .collect()
}

#[test]
fn every_function_matches_the_high_precision_reference() {
    let rows = rows();
    assert!(rows.len() > 250, "{} rows", rows.len());
    let mut mismatches = Vec::new();
    for row in &rows {
        let checked = mbexpr::parse(&row.expression)
            .map_err(|error| error.to_string())
            .and_then(|tree| mbexpr::check(&tree).map_err(|errors| errors.to_string()));
        let result = checked.and_then(|checked| {
            let program =
                mbexpr::compile(&checked, &row.names).map_err(|errors| errors.to_string())?;
            let wrt: Vec<usize> = row
                .wrt
                .iter()
                .map(|name| program.input_index(name).unwrap())
                .collect();
            program
                .evaluate(&row.values, &wrt, Order::Hessian)
                .map_err(|error| error.to_string())
        });
        let evaluation = match result {
            Ok(evaluation) => evaluation,
            Err(error) => {
                mismatches.push(format!("{}: {error}", row.expression));
                continue;
            }
        };
        let mut compare = |what: String, got: f64, want: f64| {
            if (got - want).abs() > row.tolerance * want.abs().max(1.0) {
                mismatches.push(format!(
                    "{} at {:?}: {what} is {got:e}, want {want:e} (tolerance {:e})",
                    row.expression, row.values, row.tolerance
                ));
            }
        };
        compare("the value".into(), evaluation.value, row.value);
        let gradient = evaluation.gradient.expect("order 2 has a gradient");
        for (index, want) in row.gradient.iter().enumerate() {
            compare(format!("d/d{}", row.wrt[index]), gradient[index], *want);
        }
        let hessian = evaluation.hessian.expect("order 2 has a Hessian");
        for (i, wanted_row) in row.hessian.iter().enumerate() {
            for (j, want) in wanted_row.iter().enumerate() {
                compare(
                    format!("d2/d{}d{}", row.wrt[i], row.wrt[j]),
                    hessian[(i, j)],
                    *want,
                );
            }
        }
    }
    assert!(
        mismatches.is_empty(),
        "{} mismatches:\n{}",
        mismatches.len(),
        mismatches.join("\n")
    );
}

//! The cheap ones of the hostile-input probes (`scripts/probes.py` runs
//! them all against the binary; `docs/reliability.md` has the counts): deep
//! nesting of every kind, mutations of the real corpus, mangled scene
//! files, mangled simulation datasets and garbage in REPL batch mode. None
//! may panic, hang, or give NaN.

use mbexpr::{Order, Scene};
use proptest::prelude::*;

use crate::properties::run_everything;

/// `depth` levels of one kind of nesting around `x`.
fn nested(shape: usize, depth: usize) -> String {
    match shape {
        0 => format!("{}x{}", "(".repeat(depth), ")".repeat(depth)),
        1 => format!("{}x", "-".repeat(depth)),
        2 => format!("x{}", "**x".repeat(depth)),
        3 => format!("{}x{}", "SIN(".repeat(depth), ")".repeat(depth)),
        4 => format!("{}x", "x+".repeat(depth)),
        5 => format!("{}x", "x*-".repeat(depth)),
        6 => format!("{}x{}", "(x+".repeat(depth), ")".repeat(depth)),
        _ => "(".repeat(depth),
    }
}

/// A few edits of `text`: characters and tokens deleted, inserted, repeated.
fn mutated(text: &str, edits: &[(usize, usize, u8)]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for &(kind, at, byte) in edits {
        let at = at % (chars.len() + 1);
        let insert = |chars: &mut Vec<char>, what: &str| {
            chars.splice(at..at, what.chars());
        };
        match kind % 4 {
            0 if !chars.is_empty() => {
                chars.remove(at.min(chars.len() - 1));
            }
            1 => insert(
                &mut chars,
                ["(", ")", ",", ":", "**", "-", "1E400", "IF(", "é"][usize::from(byte) % 9],
            ),
            2 if !chars.is_empty() => {
                let c = chars[at.min(chars.len() - 1)];
                insert(
                    &mut chars,
                    &c.to_string().repeat(usize::from(byte) % 40 + 2),
                );
            }
            _ => insert(&mut chars, &char::from(byte % 95 + 32).to_string()),
        }
    }
    chars.into_iter().collect()
}

fn corpus() -> Vec<String> {
    let Some(path) = crate::corpus::corpus_path("expressions.tsv") else {
        return Vec::new();
    };
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .filter_map(|line| line.rsplit('\t').next().map(str::to_string))
        .collect()
}

const SCENE: &str = include_str!("../examples/scenes/ball_between_walls.toml");
const SCENE_LINES: [&str; 10] = [
    "k = nan",
    "mode = 99",
    "time = inf",
    "[[body]]",
    "position = [1, 2]",
    "[[marker]]",
    "id = 0",
    "euler = [1e308, nan, 0]",
    "[variables]",
    "x = 1e999",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn nesting_of_any_kind_and_depth_is_a_result_or_a_located_refusal(shape in 0usize..8, depth in 1usize..3000) {
        run_everything(&nested(shape, depth));
    }

    #[test]
    fn mutated_corpus_expressions_never_panic(index in any::<prop::sample::Index>(), edits in prop::collection::vec((0usize..4, any::<usize>(), any::<u8>()), 1..5)) {
        let corpus = corpus();
        if !corpus.is_empty() {
            run_everything(&mutated(index.get::<String>(&corpus), &edits));
        }
    }

    #[test]
    fn mangled_scene_files_are_read_or_refused(edits in prop::collection::vec((0usize..4, any::<usize>(), any::<u8>()), 1..4)) {
        let mut lines: Vec<String> = SCENE.lines().map(str::to_string).collect();
        for &(kind, at, byte) in &edits {
            let at = at % lines.len();
            match kind {
                0 => lines[at] = mutated(&lines[at], &[(usize::from(byte), at, byte)]),
                1 => { lines.remove(at); }
                2 => lines.insert(at, SCENE_LINES[usize::from(byte) % SCENE_LINES.len()].to_string()),
                _ => lines[at] = lines[at].repeat(usize::from(byte) % 4 + 2),
            }
            if lines.is_empty() {
                lines.push(String::new());
            }
        }
        let text = lines.join("\n");
        let scene = match Scene::from_toml(&text) {
            Ok(scene) => scene,
            Err(errors) => {
                // Every reading error is at a place inside the file.
                for error in &errors {
                    prop_assert!(error.file_span().is_none_or(|span| span.end <= text.len()), "{error:?}");
                }
                return Ok(());
            }
        };
        for (_, text) in &scene.expressions {
            let Ok(tree) = mbexpr::parse(text) else { continue };
            let Ok(checked) = mbexpr::check(&tree) else { continue };
            let Ok(program) = mbexpr::compile_in_scene(&checked, &scene.input_names(), &scene) else { continue };
            let values = scene.values(program.inputs()).unwrap();
            let wrt: Vec<usize> = (0..values.len()).collect();
            if let Ok(evaluation) = program.evaluate(&values, &wrt, Order::Hessian) {
                prop_assert!(evaluation.value.is_finite());
                prop_assert!(evaluation.hessian.unwrap().iter().all(|h| h.is_finite()));
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn garbage_in_repl_batch_mode_gives_located_errors(lines in prop::collection::vec("[ -~]{0,30}", 1..12)) {
        let (stdout, stderr, code) = crate::cli::mbexpr(&["repl"], &lines.join("\n"));
        prop_assert!(code == 0 || code == 1, "{code}: {stderr}");
        prop_assert!(!stderr.contains("panicked"), "{stderr}");
        prop_assert!(!stdout.split_whitespace().any(|word| matches!(word, "NaN" | "inf" | "-inf")), "{stdout}");
        // Every error names its input line.
        prop_assert!(stderr.lines().filter(|line| line.starts_with("line ")).count() <= lines.len());
    }
}

/// The study's ball, whose numbers the simulation probe swaps.
const DROPPED_BALL: &str = include_str!("../examples/simulate/a4_dropped_ball.adm");

/// Numbers a careless or hostile dataset may hold.
const EXTREMES: [&str; 12] = [
    "0", "-1", "1e308", "-1e308", "1e-308", "5e-324", "1e15", "-1e-30", "1E400", "nan", "3", "1e30",
];

/// `text` with the numbers `swaps` picks (each a digit's run) replaced by
/// the extremes it names.
fn with_extremes(text: &str, swaps: &[(prop::sample::Index, usize)]) -> String {
    let mut text = text.to_string();
    for (which, extreme) in swaps {
        let numbers: Vec<(usize, usize)> = text
            .match_indices(|c: char| c.is_ascii_digit())
            .map(|(at, _)| {
                let end = text[at..]
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.'))
                    .map_or(text.len(), |n| at + n);
                (at, end)
            })
            .collect();
        let (start, end) = numbers[which.index(numbers.len())];
        text.replace_range(start..end, EXTREMES[*extreme]);
    }
    text
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// A dataset with its numbers swapped for extreme ones is simulated
    /// (every row finite) or refused with an error, within a step budget.
    #[test]
    fn mangled_simulation_datasets_run_or_stop_with_an_error(swaps in prop::collection::vec((any::<prop::sample::Index>(), 0usize..12), 1..4), dop853 in any::<bool>()) {
        use mbexpr::simulate::{self, Settings, Simulation};
        let text = with_extremes(DROPPED_BALL, &swaps);
        let dataset = mbexpr::model::read(&text, mbexpr::model::FileKind::Adm);
        let report = mbexpr::model::check_model(&text, &dataset);
        if !report.problems.is_empty() {
            return Ok(());
        }
        let Ok(model) = simulate::from_dataset(&dataset, &report) else { return Ok(()) };
        let Ok(simulation) = Simulation::new(&model) else { return Ok(()) };
        let settings = Settings {
            end: 0.5,
            steps: 5,
            max_steps: 20_000,
            method: if dop853 { mbexpr::integrate::Method::Dop853 } else { mbexpr::integrate::Method::Radau5 },
            ..Settings::default()
        };
        let mut finite = true;
        let _ = simulation.run(&settings, |time, row| {
            finite &= time.is_finite() && row.iter().all(|value| value.is_finite());
            true
        });
        prop_assert!(finite, "{text}");
    }
}

/// The View four-bar, whose numbers the View probe swaps.
const VIEW_FOUR_BAR: &str = include_str!("../examples/simulate/n_view_four_bar.cmd");

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A View file with its numbers swapped for extreme ones is read as a
    /// dataset with finite numbers only, or refused with errors inside the
    /// file; never a panic.
    #[test]
    fn mangled_view_files_read_as_finite_datasets_or_are_refused(swaps in prop::collection::vec((any::<prop::sample::Index>(), 0usize..12), 1..4)) {
        let text = with_extremes(VIEW_FOUR_BAR, &swaps);
        match mbexpr::simulate::view_dataset_text(&text) {
            Ok((dataset, _)) => {
                for token in dataset.split(|c: char| c == ',' || c == '=' || c.is_whitespace()) {
                    prop_assert!(token.parse::<f64>().map_or(true, f64::is_finite), "{token} in {dataset}");
                }
            }
            Err(mbexpr::simulate::Unread::Refused(errors)) => {
                for error in &errors {
                    if let mbexpr::simulate::Place::File(span) = error.place() {
                        prop_assert!(span.end <= text.len(), "{error:?}");
                    }
                }
            }
            Err(_) => {}
        }
    }
}

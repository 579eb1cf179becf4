//! The library's modules import only the rooms below them: the pipeline
//! flows one way (ARCHITECTURE.md, "Layers"). This reads `src/**/*.rs` and
//! reports every `crate::` path that runs back up.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

/// The library's top-level modules from the bottom up: each may import
/// only those before it. `integrate` comes right after how numbers are
/// shown in messages, because it may import nothing else of the crate (it
/// knows `f64` slices, nalgebra and its `System` trait); the ground floor
/// follows (numbers, the vocabulary, the laws, marker kinematics, the
/// operations), then the stages in pipeline order, then what stands on the
/// whole pipeline.
const LAYERS: &[&str] = &[
    "span",
    "shown",
    "integrate",
    "errors",
    "number",
    "catalog",
    "laws",
    "kinematics",
    "ops",
    "utility",
    "syntax",
    "check",
    "scene",
    "compile",
    "eval",
    "help",
    "kinks",
    "model",
    "simulate",
    "embed",
    "ffi",
];

fn source_files(folder: &Path, files: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.push(path.clone());
            source_files(&path, files);
        } else if path.extension().is_some_and(|extension| extension == "rs") {
            files.push(path);
        }
    }
}

/// The text of `source` without its comments (doc links name modules a
/// file does not import).
fn code_of(source: &str) -> String {
    source
        .lines()
        .map(|line| match line.find("//") {
            Some(start) => &line[..start],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The names `lib.rs` re-exports at the crate root, each with the module
/// it comes from (`Shown` from `shown`, `Program` from `compile`).
fn root_exports(lib: &str) -> BTreeMap<String, String> {
    let mut exports = BTreeMap::new();
    for statement in code_of(lib).split(';') {
        let Some(path) = statement.trim().strip_prefix("pub use ") else {
            continue;
        };
        let (module, names) = path.split_once("::").unwrap();
        for name in names.trim_matches(|c| c == '{' || c == '}').split(',') {
            let name = name.trim();
            let name = name.rsplit(" as ").next().unwrap();
            exports.insert(name.to_string(), module.to_string());
        }
    }
    exports
}

/// Every module `code` names through `crate::`, in a path
/// (`crate::laws::power`) or in a group (`use crate::{laws, span::Span}`).
fn imported_modules(code: &str, exports: &BTreeMap<String, String>) -> Vec<String> {
    let mut modules = Vec::new();
    let mut rest = code;
    while let Some(start) = rest.find("crate::") {
        rest = &rest[start + "crate::".len()..];
        let heads: Vec<&str> = if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            group[..end]
                .split(',')
                .map(|item| item.trim().split("::").next().unwrap())
                .collect()
        } else {
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            vec![&rest[..end]]
        };
        for head in heads.into_iter().filter(|head| !head.is_empty()) {
            let module = exports.get(head).map_or(head, String::as_str);
            modules.push(module.to_string());
        }
    }
    modules
}

/// One line per import that runs back up, or per module missing from
/// [`LAYERS`].
fn violations(source_root: &Path) -> String {
    let lib = fs::read_to_string(source_root.join("lib.rs")).unwrap();
    let exports = root_exports(&lib);
    let rank = |module: &str| LAYERS.iter().position(|layer| *layer == module);
    let mut files = Vec::new();
    source_files(source_root, &mut files);
    files.sort();
    let mut report = String::new();
    for file in files {
        let relative = file.strip_prefix(source_root).unwrap();
        let top = relative.components().next().unwrap().as_os_str();
        let top = Path::new(top).file_stem().unwrap().to_str().unwrap();
        if top == "bin" || top == "lib" {
            continue;
        }
        let Some(own) = rank(top) else {
            report.push_str(&format!(
                "{}: module `{top}` is in no layer of tests/architecture.rs\n",
                relative.display()
            ));
            continue;
        };
        if file.is_dir() {
            continue;
        }
        let code = code_of(&fs::read_to_string(&file).unwrap());
        for module in imported_modules(&code, &exports) {
            match rank(&module) {
                Some(theirs) if theirs < own || module == top => {}
                Some(_) => report.push_str(&format!(
                    "{}: `{top}` imports `{module}`, which is above it\n",
                    relative.display()
                )),
                None => {}
            }
        }
    }
    report
}

/// The rooms of `src/simulate/` from the bottom up: each may name only
/// those before it (a room is a file or folder of `simulate`; `mod.rs`
/// stands on them all). A reader builds a model and knows nothing of the
/// equations; the constraints (the joints' equations, what the equations
/// of motion add for them) know nothing of the equations of motion; the
/// equations and constraints know nothing of a run.
const SIMULATE_ROOMS: &[&str] = &[
    "error",
    "curve",
    "model",
    "read",
    "constraints",
    "equations",
    "initial",
    "run",
];

/// One line per name of a room above its own in a file of `simulate`.
fn room_violations(simulate_root: &Path) -> String {
    let rank = |room: &str| SIMULATE_ROOMS.iter().position(|name| *name == room);
    let mut files = Vec::new();
    source_files(simulate_root, &mut files);
    files.sort();
    let mut report = String::new();
    for file in files.iter().filter(|file| file.is_file()) {
        let relative = file.strip_prefix(simulate_root).unwrap();
        let room = relative.components().next().unwrap().as_os_str();
        let room = Path::new(room).file_stem().unwrap().to_str().unwrap();
        if room == "mod" {
            continue;
        }
        let Some(own) = rank(room) else {
            report.push_str(&format!(
                "simulate/{}: room `{room}` is not in SIMULATE_ROOMS\n",
                relative.display()
            ));
            continue;
        };
        let code = code_of(&fs::read_to_string(file).unwrap());
        for prefix in ["simulate::", "super::"] {
            for (start, _) in code.match_indices(prefix) {
                let rest = &code[start + prefix.len()..];
                let end = rest
                    .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                let named = &rest[..end];
                if rank(named).is_some_and(|theirs| theirs > own) {
                    report.push_str(&format!(
                        "simulate/{}: `{room}` names `{named}`, a room above it\n",
                        relative.display()
                    ));
                }
            }
        }
    }
    report
}

/// What `find` reports on a folder of `files` (path and text each).
fn report_on(files: &[(&str, &str)], find: fn(&Path) -> String) -> String {
    let root = std::env::temp_dir().join(format!(
        "mbexpr-architecture-{}-{}",
        std::process::id(),
        files[1].0.replace('/', "-")
    ));
    for (path, text) in files {
        let path = root.join(path);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(path, text).unwrap();
    }
    let report = find(&root);
    fs::remove_dir_all(&root).unwrap();
    report
}

#[test]
fn the_simulator_rooms_flow_one_way() {
    let simulate_root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/simulate");
    let report = room_violations(&simulate_root);
    assert!(report.is_empty(), "names of rooms above:\n{report}");
}

#[test]
fn a_room_naming_one_above_is_found() {
    let files = [
        ("mod.rs", "use run::Settings;\n"),
        ("read/dataset.rs", "use crate::simulate::model::Model;\n"),
        (
            "equations/mod.rs",
            "use super::run::Settings;\n// super::read\n",
        ),
        ("lounge.rs", "\n"),
    ];
    let report = report_on(&files, room_violations);
    insta::assert_snapshot!(report, @r"
    simulate/equations/mod.rs: `equations` names `run`, a room above it
    simulate/lounge.rs: room `lounge` is not in SIMULATE_ROOMS
    ");
}

/// One line per command of the binary at `binary_root` (a file or folder
/// beside `main.rs`, but `support`) whose files name another command:
/// what commands share lives in `support`, which names none.
fn command_violations(binary_root: &Path) -> String {
    let room_of = |path: &Path| {
        let first = path.components().next().unwrap().as_os_str();
        Path::new(first)
            .file_stem()
            .unwrap()
            .to_str()
            .unwrap()
            .to_string()
    };
    let mut files = Vec::new();
    source_files(binary_root, &mut files);
    files.sort();
    let commands: Vec<String> = fs::read_dir(binary_root)
        .unwrap()
        .map(|entry| room_of(Path::new(&entry.unwrap().file_name())))
        .filter(|room| room != "main" && room != "support")
        .collect();
    let mut report = String::new();
    for file in files.iter().filter(|file| file.is_file()) {
        let relative = file.strip_prefix(binary_root).unwrap();
        let room = room_of(relative);
        if room == "main" {
            continue; // the dispatcher names every command
        }
        let code = code_of(&fs::read_to_string(file).unwrap());
        for named in imported_modules(&code, &BTreeMap::new()) {
            if named != room && commands.contains(&named) {
                report.push_str(&format!(
                    "{}: `{room}` imports the command `{named}`: move what they share to support/\n",
                    relative.display()
                ));
            }
        }
    }
    report
}

#[test]
fn commands_stand_alone() {
    let binary_root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/bin/mbexpr");
    let report = command_violations(&binary_root);
    assert!(report.is_empty(), "commands that import another:\n{report}");
}

#[test]
fn a_command_importing_another_is_found() {
    let files = [
        ("main.rs", "mod check;\nmod plot;\nuse crate::plot::Args;\n"),
        ("check.rs", "use crate::support::files::read;\n"),
        (
            "plot/mod.rs",
            "use crate::{check::Format, support};\nuse crate::plot::x;\n",
        ),
        ("support/files.rs", "use crate::check::read;\n"),
    ];
    let report = report_on(&files, command_violations);
    insta::assert_snapshot!(report, @r"
    plot/mod.rs: `plot` imports the command `check`: move what they share to support/
    support/files.rs: `support` imports the command `check`: move what they share to support/
    ");
}

#[test]
fn the_pipeline_flows_one_way() {
    let source_root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let report = violations(&source_root);
    assert!(report.is_empty(), "imports that run back up:\n{report}");
}

#[test]
fn an_import_that_runs_back_up_is_found() {
    let files = [
        (
            "lib.rs",
            "pub use compile::{CompileError, Program as Compiled};\n",
        ),
        (
            "check/mod.rs",
            "use crate::{laws::power, span::Span};\n// crate::model\n",
        ),
        (
            "check/fold.rs",
            "use crate::eval::execute;\nfn f(_: crate::Compiled) {}\n",
        ),
        ("eval.rs", "use crate::{check, ops::Op};\n"),
        ("gadget.rs", "\n"),
    ];
    let report = report_on(&files, violations);
    insta::assert_snapshot!(report, @r"
    check/fold.rs: `check` imports `eval`, which is above it
    check/fold.rs: `check` imports `compile`, which is above it
    gadget.rs: module `gadget` is in no layer of tests/architecture.rs
    ");
}

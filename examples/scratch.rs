fn main() {
    for line in std::io::stdin().lines() {
        let line = line.unwrap();
        match mbexpr::parse(&line) {
            Ok(e) => match mbexpr::check(&e) {
                Ok(c) => println!("OK {}", c.root),
                Err(errs) => println!("CHECK {line}\n   {}", errs.iter().map(|e| e.to_string()).collect::<Vec<_>>().join(" | ")),
            },
            Err(e) => println!("ERR {line}\n   {e} @{:?}", e.span()),
        }
    }
}

//! Arbitrary bytes as an input script: the reader, the variable store, the
//! `$(...)` substitution and the expression evaluator must never panic or
//! hang, whatever the text.
#![no_main]

use gendpde_io::{evaluate, format_printf, ScriptReader, Variables};
use libfuzzer_sys::fuzz_target;

/// Bound on the commands pulled from one input (each `next_command` call
/// consumes at least one line, so this only guards against reader bugs).
const MAX_COMMANDS: usize = 10_000;

fuzz_target!(|bytes: &[u8]| {
    let text = String::from_utf8_lossy(bytes);
    let mut reader = ScriptReader::from_string("fuzz.in", &text);
    let mut vars = Variables::new();
    // A thermo keyword resolver, as the engine passes one.
    let thermo = |_: &str| Some(1.0);
    let none = |_: &str| None;
    for _ in 0..MAX_COMMANDS {
        match reader.next_command(&vars, &thermo) {
            Ok(None) => break,
            Ok(Some(cmd)) => {
                if cmd.name == "variable" {
                    if vars.define(&cmd).is_ok() {
                        if let Some(name) = cmd.args.first() {
                            let _ = vars.value(name, &thermo);
                            // atom-style: once per particle, names resolved per particle
                            let _ = vars.evaluate_atom(name, &thermo);
                            let _ = evaluate(&format!("v_{name}"), &vars, &none);
                        }
                    }
                }
                for arg in &cmd.args {
                    let _ = evaluate(arg, &vars, &thermo);
                }
                // `include` never reaches here: the reader follows it and
                // reports a missing file as an error.
                let _ = reader.current_location();
            }
            // Reading resumes with the next line after an error.
            Err(e) => {
                let _ = e.to_string();
            }
        }
    }
    // The raw text as an expression and as a printf format.
    let _ = evaluate(&text, &vars, &none);
    let _ = evaluate(&text, &vars, &thermo);
    let _ = format_printf(&text, 1.5);
    let _ = format_printf(&text, -0.0);
});

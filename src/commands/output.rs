//! Output commands: thermo, thermo_style, thermo_modify, dump, dump_modify, undump, write_dump (the
//! checkpoint command is `output::checkpoint`), and what the screen and log show: print,
//! log and echo.

use crate::base::args::Args;
use crate::base::script::Mode;
use crate::model::sim::Sim;
use crate::output::console::Output;
use crate::output::dump::{self, Dump, WriteDump};
use crate::output::schedule::{Frame, Span};
use crate::output::thermo::{heading, ThermoConfig};
use crate::styles::compute::{self, Compute};
use gendpde_io::{ScriptError, Variables};
use std::path::Path;

/// `thermo N`: thermo output every N steps (0: at the first and last step of a run).
pub fn thermo(thermo: &mut ThermoConfig, a: &mut Args) -> Result<(), ScriptError> {
    thermo.every = a.u64("the thermo interval")?;
    a.done()
}

/// `thermo_style one | custom KEYWORDS...`.
/// As LAMMPS, a new thermo style resets the `thermo_modify` settings (`default_norm`:
/// that of the units).
pub fn thermo_style(thermo: &mut ThermoConfig, vars: &Variables, default_norm: bool, a: &mut Args) -> Result<(), ScriptError> {
    match a.word("a thermo style (one or custom)")? {
        "custom" => {}
        "one" => {
            a.done()?;
            thermo.restyle(crate::output::thermo_settings::ONE.map(String::from).to_vec(), default_norm);
            return Ok(());
        }
        s @ ("multi" | "yaml") => return Err(a.err(format!("thermo style '{s}' is not supported (its multi-line or YAML layout is not implemented); use one or custom"))),
        s => return Err(a.err(format!("unknown thermo style '{s}'; known: one, custom"))),
    }
    let mut keys = Vec::new();
    while a.remaining() > 0 {
        let k = a.word("a keyword")?;
        let known = heading(k) != k || k.starts_with("v_") || k.starts_with("c_") || k.starts_with("f_");
        if !known {
            return Err(a.err(format!(
                "unknown thermo keyword '{k}'; known: step elapsed elaplong time dt cpu tpcpu spcpu cpuremain atoms temp tint nmean press pxx pyy pzz pe ke etotal enthalpy evdwl ecoul epair emol elong ebond eangle edihed eimp edrift nbuild ndanger vol density lx ly lz xlo xhi ylo yhi zlo zhi cella cellb cellc pxtot pytot pztot v_NAME c_ID[k] f_ID"
            )));
        }
        if let Some(name) = k.strip_prefix("v_") {
            if !vars.contains(name) {
                return Err(a.err(format!("thermo keyword {k}: no variable named '{name}'")));
            }
        }
        keys.push(k.to_string());
    }
    if keys.is_empty() {
        return Err(a.err("missing argument: expected thermo keywords"));
    }
    thermo.restyle(keys, default_norm);
    Ok(())
}

/// `thermo_modify norm yes|no | format float F | flush yes|no | temp ID | line one |
/// lost M | lost/bond M | warn M`.
pub fn thermo_modify(thermo: &mut ThermoConfig, computes: &[Box<dyn Compute>], a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected norm, format, flush, temp, line, lost, lost/bond or warn"));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "norm" => thermo.norm = a.yes_no("norm")?,
            // periodic boxes lose no particles and gendpde has no bonds: nothing to act on
            k @ ("lost" | "lost/bond") => match a.word("ignore, warn or error")? {
                "ignore" | "warn" | "error" => {}
                v => return Err(a.err(format!("Unknown thermo_modify {k} argument: {v}"))),
            },
            // gendpde's few warnings are all printed
            "warn" => match a.word("ignore, reset, default or a number")? {
                "ignore" | "reset" | "default" => {}
                n if n.parse::<u64>().is_ok() => {}
                v => return Err(a.err(format!("Expected integer parameter instead of '{v}' in input script or data file"))),
            },
            "line" => {
                let v = a.word("one, multi or yaml")?;
                if v != "one" {
                    let refused = matches!(v, "multi" | "yaml");
                    return Err(a.err(if refused { format!("thermo_modify line {v} is not supported (its multi-line or YAML layout is not implemented)") } else { format!("Unknown thermo_modify line argument: {v}") }));
                }
            }
            "temp" => {
                let id = a.word("a compute ID")?;
                match compute::find(computes, id) {
                    Some(c) if c.style().starts_with("temp") => thermo.temp = Some(id.to_string()),
                    Some(_) => return Err(a.err(format!("compute {id} does not compute a temperature (compute temp)"))),
                    None => return Err(a.err(format!("no compute with ID '{id}'"))),
                }
            }
            "flush" => thermo.flush = a.yes_no("flush")?,
            "format" => match a.word("float or line")? {
                "float" => {
                    let f = a.word("a printf format such as %15.10f")?;
                    gendpde_io::format_printf(f, 1.0).map_err(|e| a.err(format!("bad format '{f}': {e}")))?;
                    thermo.float_format = Some(f.to_string());
                }
                k => return Err(a.err(format!("thermo_modify format {k}: only 'format float' is supported"))),
            },
            k => return Err(a.err(format!("unknown keyword '{k}'; known: norm, format, flush, temp, line, lost, lost/bond, warn"))),
        }
    }
    Ok(())
}

/// `dump ID GROUP custom|atom|xyz|h5md|dcd|xtc N FILE ...`.
pub fn dump(dumps: &mut Vec<Box<dyn Dump>>, sim: &Sim, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a dump ID")?;
    if dumps.iter().any(|d| d.id() == id) {
        return Err(a.err(format!("dump ID '{id}' is in use (undump it first)")));
    }
    let dump = dump::parse(id, sim, a, false)?;
    dumps.push(dump);
    Ok(())
}

/// `dump_modify ID KEYWORD VALUES ...`.
pub fn dump_modify(dumps: &mut [Box<dyn Dump>], a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a dump ID")?;
    let dump = dumps.iter_mut().find(|d| d.id() == id).ok_or_else(|| a.err(format!("no dump with ID '{id}'")))?;
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected dump_modify keywords"));
    }
    while a.remaining() > 0 {
        let key = a.word("a keyword")?;
        dump.modify(key, a)?;
    }
    Ok(())
}

/// `undump ID`: closes the dump's file.
pub fn undump(dumps: &mut Vec<Box<dyn Dump>>, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a dump ID")?;
    a.done()?;
    let k = dumps.iter().position(|d| d.id() == id).ok_or_else(|| a.err(format!("no dump with ID '{id}'")))?;
    dumps.remove(k).close().map_err(|e| a.err(e))
}

/// `write_dump GROUP STYLE FILE ARGS... [modify ...]`: one frame of a dump of any style.
pub fn write_dump(sim: &Sim, vars: &Variables, thermo: &ThermoConfig, out: &mut Output, a: &mut Args) -> Result<(), ScriptError> {
    let dump = WriteDump::parse(sim, a)?;
    let sys = sim.system.as_ref().ok_or_else(|| a.err("write_dump before create_box"))?;
    let run = Span { first: sys.clock.step, last: sys.clock.step };
    dump.write(&mut Frame { sim, sys, vars, thermo, out, run, cpu: 0.0 }).map_err(|e| a.err(e))
}

/// `print TEXT [screen yes|no]`, TEXT substituted as it executes (LAMMPS's print).
pub fn print(out: &mut Output, a: &mut Args, substitute: &dyn Fn(&str) -> Result<String, String>) -> Result<(), ScriptError> {
    let text = a.word("the text to print")?;
    let text = substitute(text).map_err(|e| a.err(e))?;
    let mut screen = true;
    while a.remaining() > 0 {
        match a.word("keyword")? {
            "screen" => screen = a.yes_no("screen")?,
            k => return Err(a.err(format!("unknown keyword '{k}'; known: screen"))),
        }
    }
    if screen { out.line(&text) } else { out.log_line(&text) }
    Ok(())
}

/// `log FILE [append]` or `log none`; a check opens no file.
pub fn log(out: &mut Output, mode: Mode, a: &mut Args) -> Result<(), ScriptError> {
    let file = a.word("a log file name")?;
    let append = match a.peek() {
        Some("append") => {
            a.word("append")?;
            true
        }
        _ => false,
    };
    a.done()?;
    if file == "none" {
        out.close_log();
    } else if mode == Mode::Run {
        out.open_log(Path::new(file), append).map_err(|e| a.err(format!("cannot open log file '{file}': {e}")))?;
    }
    Ok(())
}

/// `echo none|screen|log|both`: whether commands are echoed to the screen too (gendpde
/// always echoes them to the log).
pub fn echo(a: &mut Args) -> Result<bool, ScriptError> {
    let screen = match a.word("none, screen, log or both")? {
        "screen" | "both" => true,
        "none" | "log" => false,
        s => return Err(a.err(format!("expected none, screen, log or both, got '{s}'"))),
    };
    a.done()?;
    Ok(screen)
}

//! The functions of equal-style formulas, as LAMMPS's variable.cpp defines them: the math
//! functions of numbers (`math_function`: sqrt ... cwiggle, ternary, sign) and the feature
//! functions of one word (`is_file`, `is_os`, `extract_setting`).
//!
//! The functions of the step (ramp, stagger, logfreq, stride, vdisplace, swiggle, ...)
//! read `step` and `dt` and the reserved names below through the resolver of thermo
//! keywords; no formula can spell a reserved name (the colon), so only the program answers
//! them.

/// First step of the current run, 0 between runs (LAMMPS's beginstep).
pub const RUN_BEGIN: &str = "run:begin";
/// Last step of the current run, 0 between runs (LAMMPS's endstep).
pub const RUN_END: &str = "run:end";
/// 1 while a run is set up or stepped, 0 between runs (LAMMPS's whichflag).
pub const RUN_ACTIVE: &str = "run:active";
/// `setting:NAME`: an `extract_setting(NAME)` that depends on the system (box_exist,
/// world_size, world_rank, ntypes, nlocal).
pub const SETTING: &str = "setting:";

/// Functions whose argument is a word, not a formula: LAMMPS's feature functions and its
/// group functions (of group, dimension and region IDs, which `resolve` evaluates as
/// `name(arg,...)`).
pub(crate) const WORD_FUNCTIONS: [&str; 16] = [
    "is_file", "is_os", "extract_setting", "is_active", "is_available", "is_defined", "label2type", "is_typelabel",
    "count", "mass", "xcm", "vcm", "fcm", "bound", "gyration", "ke",
];

/// The group functions among [`WORD_FUNCTIONS`].
const GROUP_FUNCTIONS: [&str; 8] = ["count", "mass", "xcm", "vcm", "fcm", "bound", "gyration", "ke"];

/// LAMMPS's MAXBIGINT_DOUBLE: the step stride() returns past its last one.
const MAX_STEP: f64 = (i64::MAX - 512) as f64;

/// Most iterations logfreq2() and logfreq3() may take to find the next step (LAMMPS's
/// loops have no bound: arguments such as logfreq2(1,1e12,2) would spin for hours).
const MAX_ITERATIONS: u64 = 100_000_000;

/// The value of math function `name` of `args`; domain errors are reported, never NaN or
/// inf.
pub(crate) fn math(name: &str, args: &[f64], resolve: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
    let arity = |n: usize| if args.len() == n { Ok(()) } else { Err(format!("{name}() takes {n} argument{}, got {}", if n == 1 { "" } else { "s" }, args.len())) };
    // before the box exists the step is 0 and no run is active
    let get = |key: &str| Ok::<f64, String>(resolve(key).unwrap_or(0.0));
    let invalid = |why: &str| Err(format!("Invalid math function in variable formula: {name}() {why}"));
    // the step and LAMMPS's integer arguments (static_cast<bigint>)
    let step = || get("step").map(|s| s as i64);
    let int = |k: usize| args[k] as i64;
    // (step - beginstep) * dt
    let elapsed = || {
        let steps = get("step")? - get(RUN_BEGIN)?;
        if steps == 0.0 { Ok(0.0) } else { resolve("dt").map(|dt| steps * dt).ok_or_else(|| format!("{name}() reads the timestep: define the box first")) }
    };
    let value = match name {
        "sqrt" | "exp" | "ln" | "log" | "abs" | "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "floor" | "ceil" | "round" | "sign" => {
            arity(1)?;
            let x = args[0];
            match name {
                "sqrt" => x.sqrt(),
                "exp" => x.exp(),
                "ln" => x.ln(),
                "log" => x.log10(),
                "abs" => x.abs(),
                "sin" => x.sin(),
                "cos" => x.cos(),
                "tan" => x.tan(),
                "asin" => x.asin(),
                "acos" => x.acos(),
                "atan" => x.atan(),
                "floor" => x.floor(),
                "ceil" => x.ceil(),
                // LAMMPS's MYROUND: halves round up (round(-2.5) = -2)
                "round" if x - x.floor() >= 0.5 => x.ceil(),
                "round" => x.floor(),
                _ if x >= 0.0 => 1.0,
                _ => -1.0,
            }
        }
        "atan2" | "min" | "max" => {
            arity(2)?;
            let (a, b) = (args[0], args[1]);
            match name {
                "atan2" => a.atan2(b),
                "min" => a.min(b),
                _ => a.max(b),
            }
        }
        "ternary" => {
            arity(3)?;
            if args[0] != 0.0 { args[1] } else { args[2] }
        }
        "ramp" => {
            arity(2)?;
            if get(RUN_ACTIVE)? == 0.0 {
                args[0]
            } else {
                let (begin, end) = (get(RUN_BEGIN)?, get(RUN_END)?);
                let mut delta = get("step")? - begin;
                if delta != 0.0 && begin != end {
                    delta /= end - begin;
                }
                args[0] + delta * (args[1] - args[0])
            }
        }
        "stagger" => {
            arity(2)?;
            let (a, b) = (int(0), int(1));
            if a <= 0 || b <= 0 || a <= b {
                return invalid("needs 0 < y < x");
            }
            let lower = step()? / a * a;
            (if step()? - lower < b { lower + b } else { lower + a }) as f64
        }
        "logfreq" => {
            arity(3)?;
            let (a, b, c) = (int(0), int(1), int(2));
            if a <= 0 || b <= 0 || c <= 0 || b >= c {
                return invalid("needs positive x, y, z and y < z");
            }
            let s = step()?;
            if s < a {
                a as f64
            } else {
                let mut lower = a;
                while let Some(next) = c.checked_mul(lower).filter(|n| s >= *n) {
                    lower = next;
                }
                let multiple = s / lower;
                (if multiple < b { (multiple + 1) * lower } else { lower * c }) as f64
            }
        }
        "logfreq2" => {
            arity(3)?;
            let (a, b, c) = (int(0), int(1), int(2));
            // z = 1 would never advance (LAMMPS loops forever)
            if a <= 0 || b <= 0 || c <= 1 {
                return invalid("needs positive x and y and z > 1");
            }
            let s = step()? as f64;
            let mut value = a as f64;
            if s >= value {
                let mut delta = a as f64 * (c as f64 - 1.0) / b as f64;
                let mut count = 0;
                while s >= value {
                    value += delta;
                    count += 1;
                    if count % b == 0 {
                        delta *= c as f64;
                    }
                    if count as u64 > MAX_ITERATIONS {
                        return invalid("takes too many iterations to reach the step");
                    }
                }
            }
            value.ceil()
        }
        "logfreq3" => {
            arity(3)?;
            let (a, b, c) = (int(0), int(1), int(2));
            if a <= 0 || b <= 1 || c <= 0 || c - a + 1 < b {
                return invalid("needs positive x and z, y > 1 and z - x + 1 >= y");
            }
            let s = step()?;
            let mut value = a as f64;
            if s >= a {
                let (mut logsp, factor, mut linsp) = (a as f64, (c as f64 / a as f64).powf(1.0 / (b - 1) as f64), a);
                while s as f64 >= value {
                    if (linsp - a) as u64 > MAX_ITERATIONS {
                        return invalid("takes too many iterations to reach the step");
                    }
                    logsp *= factor;
                    linsp += 1;
                    value = if linsp as f64 > logsp { linsp as f64 } else { logsp.ceil() - ((logsp.ceil() as i64 - 1) / c) as f64 };
                }
            }
            if s > c {
                return Err("Calls to variable exceeded limit (logfreq3)".into());
            }
            value
        }
        "stride" => {
            arity(3)?;
            let (a, b, c) = (int(0), int(1), int(2));
            if a < 0 || b < 0 || c <= 0 || a > b {
                return invalid("needs 0 <= x <= y and z > 0");
            }
            let s = step()?;
            if s < a {
                a as f64
            } else if s < b {
                let v = (a + (s - a) / c * c + c) as f64;
                if v > b as f64 { MAX_STEP } else { v }
            } else {
                MAX_STEP
            }
        }
        "stride2" => {
            arity(6)?;
            let [a, b, c, d, e, f] = [0, 1, 2, 3, 4, 5].map(int);
            if a < 0 || b < 0 || c <= 0 || a > b || d < 0 || e < 0 || f <= 0 || d > e || d < a || e > b {
                return invalid("needs 0 <= x <= a <= b <= y and positive z, c");
            }
            let s = step()?;
            let outer = |from: i64| a + (from - a) / c * c + c;
            if s < a {
                a as f64
            } else if s < b {
                if s < d || s > e {
                    let v = outer(s);
                    (if s < d && v > d { d } else { v }) as f64
                } else {
                    let v = d + (s - d) / f * f + f;
                    if v <= e {
                        v as f64
                    } else if outer(e) > b {
                        MAX_STEP
                    } else {
                        outer(e) as f64
                    }
                }
            } else {
                MAX_STEP
            }
        }
        "vdisplace" => {
            arity(2)?;
            args[0] + args[1] * elapsed()?
        }
        "swiggle" | "cwiggle" => {
            arity(3)?;
            if args[2] == 0.0 {
                return Err(format!("Invalid {name}(x,y,z) function in variable formula: z must be > 0"));
            }
            let phase = 2.0 * std::f64::consts::PI / args[2] * elapsed()?;
            args[0] + args[1] * if name == "swiggle" { phase.sin() } else { 1.0 - phase.cos() }
        }
        "random" | "normal" => return Err(format!("{name}() is not supported (LAMMPS's Marsaglia generator of equal-style formulas is not implemented)")),
        _ => return Err(format!("unknown function '{name}()'")),
    };
    if value.is_finite() {
        Ok(value)
    } else {
        let shown: Vec<String> = args.iter().map(ToString::to_string).collect();
        Err(format!("{name}({}) is undefined", shown.join(",")))
    }
}

/// The value of feature function `name` of the word `arg` (LAMMPS's special functions), or
/// of group function `name` of its comma-separated IDs.
pub(crate) fn word(name: &str, arg: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
    let arg = arg.trim();
    if GROUP_FUNCTIONS.contains(&name) {
        let call = format!("{name}({})", arg.split(',').map(str::trim).collect::<Vec<_>>().join(","));
        return resolve(&call).ok_or_else(|| format!("group function {call}: no such group or region, or a wrong argument (or no box yet)"));
    }
    let truth = |b: bool| if b { 1.0 } else { 0.0 };
    Ok(match name {
        "is_file" => truth(std::fs::File::open(arg).is_ok()),
        "is_os" => {
            let os = format!("{} {}", std::env::consts::OS, std::env::consts::ARCH);
            truth(os_matches(arg, &os))
        }
        "extract_setting" => match arg {
            "dimension" => 3.0,
            "bigint" => 8.0,
            "tagint" | "imageint" => 4.0,
            "triclinic" | "universe_rank" => 0.0,
            "universe_size" | "nthreads" => 1.0,
            "box_exist" => resolve(&format!("{SETTING}box_exist")).unwrap_or(0.0),
            "world_size" | "world_rank" | "ntypes" | "nlocal" => {
                resolve(&format!("{SETTING}{arg}")).ok_or_else(|| format!("extract_setting({arg}) reads the system: define the box first"))?
            }
            _ => return Err(format!("Unknown setting {arg} for extract_setting() function in variable formula")),
        },
        _ => return Err(format!("{name}() is not supported (gendpde has no LAMMPS package, style or type-label registry to query)")),
    })
}

/// Whether the OS description `os` ("linux x86_64") matches `pattern`, a LAMMPS regex of
/// literals with an optional leading `^` (case-insensitive).
fn os_matches(pattern: &str, os: &str) -> bool {
    let os = os.to_lowercase();
    match pattern.to_lowercase().strip_prefix('^') {
        Some(p) => os.starts_with(p),
        None => os.contains(&pattern.to_lowercase()),
    }
}

//! gendpde: Generalised energy-conserving Dissipative Particle Dynamics.

use clap::{Parser, Subcommand};
use gendpde::{signals, AppError, Interpreter, Mode, Output};
use gendpde_engine::Transport;
use std::io::{IsTerminal, Read};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "gendpde", version, about = "GenDPDE particle simulation with LAMMPS-style input scripts")]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(clap::Args)]
struct ScriptArgs {
    /// Input script (LAMMPS syntax; see docs/commands/).
    input: PathBuf,
    /// Define an index variable: -var NAME VALUE (repeatable).
    #[arg(long = "var", num_args = 2, value_names = ["NAME", "VALUE"], action = clap::ArgAction::Append)]
    var: Vec<String>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run an input script.
    Run {
        #[command(flatten)]
        script: ScriptArgs,
        /// Log file (default log.gendpde; `none` for no log).
        #[arg(long = "log", default_value = "log.gendpde")]
        log: String,
    },
    /// Parse and validate an input script without running any step.
    Check {
        #[command(flatten)]
        script: ScriptArgs,
    },
    /// Make an H5MD file whose writer was killed or ran out of disk readable again
    /// (like `h5clear -s -i`); never while a run still writes it.
    H5mdRepair {
        file: PathBuf,
    },
    /// Evaluate a particle EOS: gendpde eos MODEL PARAMS... --theta T --n N (or --u U).
    /// MODEL and PARAMS as in `fix ID all eos/MODEL PARAMS`, e.g. `vdw 60 2.4682 1.4142`.
    Eos {
        /// vdw, lj, ideal, cv, density or linear.
        model: String,
        /// The EOS parameters (C_V first).
        #[arg(allow_negative_numbers = true)]
        params: Vec<String>,
        #[arg(long)]
        theta: Option<f64>,
        #[arg(long)]
        u: Option<f64>,
        #[arg(long)]
        n: f64,
    },
    /// Macroscopic state of an LTh fluid (argon paper eqs 78, 85-91, 99) from a g(r) file
    /// (`--gr FILE`: lines `r g`, or LAMMPS's compute rdf via fix ave/time) or from the
    /// self-consistent HNC of eqs 119-120 (`--hnc`).
    LthMacro {
        /// CV ALPHA KAPPA_T PI00 THETA0 N00, as `fix eos/lth`.
        #[arg(num_args = 6, allow_negative_numbers = true)]
        params: Vec<f64>,
        /// Density cutoff R_cut (quadratic weight).
        #[arg(long)]
        rc: f64,
        /// f_cut of the corrected volume (R~ = R_cut / f_cut).
        #[arg(long)]
        fcut: f64,
        /// Bulk number density c.
        #[arg(long)]
        density: f64,
        /// Temperature (k_B = 1 units of theta).
        #[arg(long)]
        temperature: f64,
        #[arg(long, conflicts_with = "hnc", required_unless_present = "hnc")]
        gr: Option<PathBuf>,
        #[arg(long)]
        hnc: bool,
    },
    /// Reduced LTh model parameters of argon (argon paper, eqs 101-117; Tables 1, 2, 9).
    LthParams {
        /// liquid or supercritical.
        #[arg(long)]
        state: String,
    },
}

/// `gendpde lth-params`: one `name value` line per parameter.
fn lth_params(state: &str) -> ExitCode {
    use gendpde_potentials::lth_params::{LthParams, Reference};
    let reference = match state {
        "liquid" => Reference::liquid_argon(),
        "supercritical" => Reference::supercritical_argon(),
        _ => {
            eprintln!("ERROR: unknown state '{state}' (liquid or supercritical)");
            return ExitCode::FAILURE;
        }
    };
    for (name, value) in LthParams::derive(&reference).lines() {
        println!("{name} {}", gendpde_io::format_g(value, 8));
    }
    ExitCode::SUCCESS
}

/// `gendpde lth-macro`: one `name value` line per quantity.
fn lth_macro(p: &[f64], rc: f64, fcut: f64, density: f64, temperature: f64, gr: Option<PathBuf>) -> ExitCode {
    use gendpde::lth_macro::{evaluate, fluid, Source};
    let eos = gendpde_potentials::eos::Lth::new(p[0], p[1], p[2], p[3], p[4], p[5]);
    let source = gr.as_deref().map_or(Source::Hnc, Source::File);
    print_lines(fluid(eos, rc, fcut, density, temperature).and_then(|f| evaluate(&f, source)), 10)
}

/// `name value` lines with `digits` significant digits, or the error on stderr.
fn print_lines<S: std::fmt::Display>(result: Result<Vec<(S, f64)>, String>, digits: usize) -> ExitCode {
    match result {
        Ok(lines) => {
            for (name, value) in lines {
                println!("{name} {}", gendpde_io::format_g(value, digits));
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("ERROR: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `gendpde eos`: one `name value` line per quantity.
fn eos(model: String, params: Vec<String>, theta: Option<f64>, u: Option<f64>, n: f64) -> ExitCode {
    let mut args = vec!["eos".to_string(), "all".to_string(), format!("eos/{model}")];
    args.extend(params);
    let cmd = gendpde_io::Command { name: "fix".into(), args, loc: gendpde_io::Location { file: "<command line>".into(), line: 0 } };
    let result = gendpde::styles::fix::parse_fix(&cmd, 1.0, &[]).map_err(|e| e.message).and_then(|fix| match fix.style {
        gendpde::styles::fix::FixStyle::Eos(m) => m.describe(theta, u, n),
        _ => Err(format!("unknown EOS model '{model}'")),
    });
    print_lines(result, 15)
}

/// What a script reads and where its output goes.
struct Session {
    input: Input,
    mode: Mode,
    /// `-var NAME VALUE...`
    vars: Vec<(String, Vec<String>)>,
    /// Log file (None or `none`: no log).
    log: Option<String>,
    screen: bool,
    /// Echo commands to the screen as well (`-echo screen|both`).
    echo_screen: bool,
}

enum Input {
    File(PathBuf),
    /// The script on standard input (`gendpde < in.x`), read by rank 0.
    Stdin,
}

/// LAMMPS's command line: `gendpde [-in FILE] [-var NAME VALUE...] [-log FILE] [-echo STYLE]
/// [-screen none] [-nocite] [-nonbuf]`, the script on standard input without `-in`.
fn lammps_command_line(args: &[String]) -> Result<Session, String> {
    let mut s = Session { input: Input::Stdin, mode: Mode::Run, vars: Vec::new(), log: Some("log.lammps".into()), screen: true, echo_screen: false };
    let mut i = 0;
    let value = |i: usize, flag: &str| args.get(i + 1).cloned().ok_or_else(|| format!("option {flag} needs a value"));
    while i < args.len() {
        let flag = args[i].as_str();
        match flag {
            "-in" | "-i" => s.input = Input::File(value(i, flag)?.into()),
            "-log" | "-l" => s.log = Some(value(i, flag)?),
            "-screen" | "-sc" => match value(i, flag)?.as_str() {
                "none" => s.screen = false,
                f => return Err(format!("-screen {f}: only -screen none is supported (the screen goes to standard output)")),
            },
            "-echo" | "-e" => {
                s.echo_screen = match value(i, flag)?.as_str() {
                    "screen" | "both" => true,
                    "log" | "none" => false,
                    e => return Err(format!("-echo {e}: expected none, screen, log or both")),
                }
            }
            "-var" | "-v" => {
                let name = value(i, flag)?;
                let values: Vec<String> = args[i + 2..].iter().take_while(|a| !a.starts_with('-')).cloned().collect();
                if values.is_empty() {
                    return Err(format!("-var {name} needs at least one value"));
                }
                i += values.len();
                s.vars.push((name, values));
            }
            "-nocite" | "-nc" | "-nonbuf" | "-nb" => {
                i += 1;
                continue;
            }
            "-sf" | "-suffix" | "-pk" | "-package" | "-k" | "-kokkos" | "-p" | "-partition" | "-pl" | "-plog" | "-ps" | "-pscreen"
            | "-ro" | "-reorder" | "-r2data" | "-restart2data" | "-r2dump" | "-restart2dump" | "-m" | "-mpicolor" | "-c" | "-cite"
            | "-sr" | "-skiprun" | "-mdi" => return Err(format!("LAMMPS option {flag} is not supported")),
            _ => return Err(format!("unknown command-line option '{flag}' (see gendpde --help)")),
        }
        i += 2;
    }
    Ok(s)
}

/// LAMMPS spells long options with one dash (`-var`, `-log`, `-in`).
fn lammps_style_args() -> Vec<String> {
    std::env::args()
        .map(|a| match a.as_str() {
            "-var" | "-v" => "--var".into(),
            "-log" | "-l" => "--log".into(),
            "-in" | "-i" => String::new(),
            _ => a,
        })
        .filter(|a| !a.is_empty())
        .collect()
}

/// MPI_COMM_WORLD with the `mpi` feature when started by an MPI launcher, else a
/// single rank (a plain `gendpde run` never initialises MPI).
#[cfg(feature = "mpi")]
fn transport() -> Box<dyn Transport> {
    let launched = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"].iter().any(|v| std::env::var_os(v).is_some());
    match launched.then(gendpde_engine::comm::MpiTransport::init).flatten() {
        Some(t) => Box::new(t),
        None => Box::new(gendpde_engine::Local),
    }
}

#[cfg(not(feature = "mpi"))]
fn transport() -> Box<dyn Transport> {
    Box::new(gendpde_engine::Local)
}

/// Rank 0's `text` on every rank.
fn broadcast(t: &dyn Transport, text: String) -> String {
    let len = t.all_gather(&[text.len() as u64])[0] as usize;
    let words = len.div_ceil(8);
    let mut local = vec![0u64; words];
    if t.rank() == 0 {
        for (w, chunk) in local.iter_mut().zip(text.as_bytes().chunks(8)) {
            let mut b = [0u8; 8];
            b[..chunk.len()].copy_from_slice(chunk);
            *w = u64::from_le_bytes(b);
        }
    }
    let bytes: Vec<u8> = t.all_gather(&local)[..words].iter().flat_map(|w| w.to_le_bytes()).take(len).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    std::panic::set_hook(Box::new(|info| {
        eprintln!("ERROR: internal error in gendpde (please report it): {info}");
    }));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let lammps = match args.first().map(String::as_str) {
        None => !std::io::stdin().is_terminal(),
        Some(a) => a.starts_with('-') && !a.starts_with("--") && !matches!(a, "-h" | "-V"),
    };
    if lammps {
        return match lammps_command_line(&args) {
            Ok(session) => run(session),
            Err(e) => {
                eprintln!("ERROR: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let cli = Cli::parse_from(lammps_style_args());
    let pairs = |v: Vec<String>| v.chunks(2).map(|p| (p[0].clone(), p[1..].to_vec())).collect();
    let session = match cli.command {
        Cmd::Run { script, log } => {
            Session { input: Input::File(script.input), mode: Mode::Run, vars: pairs(script.var), log: Some(log), screen: true, echo_screen: false }
        }
        Cmd::Check { script } => {
            Session { input: Input::File(script.input), mode: Mode::Check, vars: pairs(script.var), log: None, screen: true, echo_screen: false }
        }
        Cmd::Eos { model, params, theta, u, n } => return eos(model, params, theta, u, n),
        Cmd::LthParams { state } => return lth_params(&state),
        Cmd::LthMacro { params, rc, fcut, density, temperature, gr, .. } => {
            return lth_macro(&params, rc, fcut, density, temperature, gr)
        }
        Cmd::H5mdRepair { file } => {
            return match gendpde_io::h5md::repair_h5md(&file).and_then(|_| gendpde_io::check_h5md(&file)) {
                Ok(summary) => {
                    println!("{}: {} frames of {} particles", file.display(), summary.frames, summary.particles);
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("ERROR: {}", e.0);
                    ExitCode::FAILURE
                }
            }
        }
    };
    run(session)
}

/// Runs (or checks) the script of `session`.
fn run(session: Session) -> ExitCode {
    let start = std::time::Instant::now();
    let transport = transport();
    // after MPI's initialisation, which may install handlers of its own
    if session.mode == Mode::Run {
        if let Err(e) = signals::install() {
            eprintln!("ERROR: cannot install the signal handlers: {e}");
            return ExitCode::FAILURE;
        }
    }
    let rank = transport.rank();
    let mut out = Output::new(rank == 0 && session.screen);
    if let Some(log) = session.log.filter(|l| l != "none" && rank == 0) {
        if let Err(e) = out.open_log(std::path::Path::new(&log), false) {
            eprintln!("ERROR: cannot open log file '{log}': {e}");
            return ExitCode::FAILURE;
        }
    }
    let mode = session.mode;
    let stdin = match session.input {
        Input::Stdin => {
            let mut text = String::new();
            if rank == 0 {
                if let Err(e) = std::io::stdin().read_to_string(&mut text) {
                    eprintln!("ERROR: cannot read the input script from standard input: {e}");
                    return ExitCode::FAILURE;
                }
            }
            Some(broadcast(transport.as_ref(), text))
        }
        Input::File(_) => None,
    };
    let mut it = Interpreter::with_transport(mode, out, transport);
    it.echo_screen = session.echo_screen;
    for (name, values) in session.vars {
        it.vars.set_command_line(&name, values);
    }
    let (result, name) = match (&session.input, stdin) {
        (Input::File(path), _) => (it.execute_file(path), path.display().to_string()),
        (Input::Stdin, text) => (it.execute_str("stdin", &text.unwrap_or_default()), "stdin".to_string()),
    };
    // `quit` ends the script as its end would, with its status
    let (result, status) = match result {
        Err(AppError::Quit { status }) => (Ok(()), status),
        other => (other, 0),
    };
    match result {
        Ok(()) => {
            if mode == Mode::Check {
                it.out.line(&format!("{name}: OK"));
            }
            let s = start.elapsed().as_secs();
            it.out.line(&format!("Total wall time: {}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60));
            // a signal outside a run: the script went on to its end
            match signals::received().load(std::sync::atomic::Ordering::Relaxed) {
                0 => ExitCode::from(status),
                sig => {
                    it.out.line(&format!("{} received outside a run; the script ended", signals::name(sig)));
                    ExitCode::from((128 + sig) as u8)
                }
            }
        }
        Err(e) => {
            // every rank holds the same error (a failed step's is agreed over the ranks)
            let (msg, code) = match &e {
                AppError::Interrupted { signal, .. } => (e.to_string(), ExitCode::from((128 + signal) as u8)),
                _ => (format!("ERROR: {e}"), ExitCode::FAILURE),
            };
            if rank == 0 {
                it.out.log_line(&msg);
                eprintln!("{msg}");
            }
            it.out.close_log();
            code
        }
    }
}

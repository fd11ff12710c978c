//! Screen and log-file output, as LAMMPS writes them; each log line is flushed as it is
//! printed.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Writes to stdout and, when open, to the log file.
pub struct Output {
    log: Option<BufWriter<File>>,
    pub screen: bool,
}

impl Output {
    pub fn new(screen: bool) -> Self {
        Self { log: None, screen }
    }

    /// Opens (or appends to) a log file, closing the previous one.
    pub fn open_log(&mut self, path: &Path, append: bool) -> io::Result<()> {
        self.flush();
        let file = File::options().create(true).write(true).append(append).truncate(!append).open(path)?;
        self.log = Some(BufWriter::new(file));
        Ok(())
    }

    pub fn close_log(&mut self) {
        self.flush();
        self.log = None;
    }

    /// A line on the screen and in the log.
    pub fn line(&mut self, text: &str) {
        if self.screen {
            println!("{text}");
        }
        self.log_line(text);
    }

    /// A line in the log only (the echo of script commands). Every line reaches the
    /// file (the operating system) as it is written, so a killed run keeps its log.
    pub fn log_line(&mut self, text: &str) {
        if let Some(log) = &mut self.log {
            if writeln!(log, "{text}").and_then(|()| log.flush()).is_err() {
                eprintln!("WARNING: writing the log file failed; closing it");
                self.log = None;
            }
        }
    }

    /// Puts the log on disk (`thermo_modify flush yes`: it then survives a crash of the
    /// machine, not only of gendpde).
    pub fn sync(&mut self) {
        if let Some(log) = &mut self.log {
            if log.get_ref().sync_data().is_err() {
                eprintln!("WARNING: syncing the log file failed");
            }
        }
    }

    pub fn flush(&mut self) {
        if let Some(log) = &mut self.log {
            let _ = log.flush();
        }
        let _ = io::stdout().flush();
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        self.flush();
    }
}

//! Screen and log-file output, as LAMMPS writes them; each log line is flushed as it is
//! printed. A log that cannot be written (a full disk) stops the script naming the file;
//! a screen whose reader went away (`gendpde run in.x | head`) stops the run as SIGPIPE
//! would, after the step, with the state saved.

use crate::base::signals;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes to stdout and, when open, to the log file.
pub struct Output {
    log: Option<(BufWriter<File>, PathBuf)>,
    pub screen: bool,
    /// Why the log failed, until the interpreter takes it.
    failed: Option<String>,
}

impl Output {
    pub fn new(screen: bool) -> Self {
        Self { log: None, screen, failed: None }
    }

    /// Opens (or appends to) a log file, closing the previous one.
    pub fn open_log(&mut self, path: &Path, append: bool) -> io::Result<()> {
        self.flush();
        let file = File::options().create(true).write(true).append(append).truncate(!append).open(path)?;
        self.log = Some((BufWriter::new(file), path.to_path_buf()));
        Ok(())
    }

    /// The failure of the log file since the last call, naming the file.
    pub fn take_error(&mut self) -> Option<String> {
        self.failed.take()
    }

    pub fn close_log(&mut self) {
        self.flush();
        self.log = None;
    }

    /// A line on the screen and in the log.
    pub fn line(&mut self, text: &str) {
        if self.screen {
            if let Err(e) = writeln!(io::stdout().lock(), "{text}") {
                // nobody reads the screen any more: stop as SIGPIPE would
                self.screen = false;
                if e.kind() == io::ErrorKind::BrokenPipe {
                    signals::received().store(signals::SIGPIPE, std::sync::atomic::Ordering::Relaxed);
                }
            }
        }
        self.log_line(text);
    }

    /// A line in the log only (the echo of script commands). Every line reaches the
    /// file (the operating system) as it is written, so a killed run keeps its log.
    pub fn log_line(&mut self, text: &str) {
        if let Some((log, path)) = &mut self.log {
            if let Err(e) = writeln!(log, "{text}").and_then(|()| log.flush()) {
                self.failed = Some(format!("log file {}: {e}", path.display()));
                self.log = None;
            }
        }
    }

    /// Puts the log on disk (`thermo_modify flush yes`: it then survives a crash of the
    /// machine, not only of gendpde).
    pub fn sync(&mut self) {
        if let Some((log, path)) = &mut self.log {
            if let Err(e) = log.get_ref().sync_data() {
                self.failed = Some(format!("log file {}: {e}", path.display()));
            }
        }
    }

    pub fn flush(&mut self) {
        if let Some((log, _)) = &mut self.log {
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

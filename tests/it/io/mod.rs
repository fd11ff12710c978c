//! Files and the command line: restarts, H5MD files and their readers, text, DCD and XTC
//! dumps, `gendpde`'s subcommands and messages.

mod cli;
mod dump_formats;
mod dumps;
mod h5md_readers;
#[allow(clippy::module_inception)]
mod io;

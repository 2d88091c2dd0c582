//! Printing for the command line. Standard output closed by its reader (`dataink schema | head`)
//! is a normal end: the process exits with code 0 and says nothing. Standard error that cannot
//! be written is ignored, so messages never turn into a panic.

use std::fmt;
use std::io::{self, Write};

/// Write to standard output; on a closed pipe, end the process with code 0.
pub fn out(args: fmt::Arguments<'_>) {
    let written = {
        let mut stdout = io::stdout().lock();
        stdout.write_fmt(args).and_then(|()| stdout.flush())
    };
    if let Err(e) = written {
        if e.kind() == io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        err(format_args!("error: cannot write to standard output: {e}\n"));
        std::process::exit(2);
    }
}

/// Write to standard error, ignoring failures (there is nowhere left to report them).
pub fn err(args: fmt::Arguments<'_>) {
    let _ = io::stderr().lock().write_fmt(args);
}

/// `println!` through [`out`].
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::output::out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprint!` through [`err`].
macro_rules! errs {
    ($($arg:tt)*) => {
        $crate::cli::output::err(format_args!($($arg)*))
    };
}

/// `eprintln!` through [`err`].
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::cli::output::err(format_args!("{}\n", format_args!($($arg)*)))
    };
}

pub(crate) use {errln, errs, outln};

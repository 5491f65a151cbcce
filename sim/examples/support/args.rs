//! The examples' command lines: `--flag a,b,c` lists, and bad input refused with the usage
//! line and exit status 2 (never a panic).

use std::str::FromStr;

/// An example's name and usage line, for its refusals.
pub struct Cli {
    pub name: &'static str,
    pub usage: &'static str,
}

impl Cli {
    /// Prints `message` and the usage line, and exits with status 2.
    pub fn refuse(&self, message: &str) -> ! {
        eprintln!("{}: {message}\n{}", self.name, self.usage);
        std::process::exit(2)
    }

    /// The comma-separated values of `flag` (`_` allowed as a digit separator), or a
    /// refusal naming the flag.
    pub fn list<T: FromStr>(&self, flag: &str, value: Option<&String>) -> Vec<T> {
        let value = value.unwrap_or_else(|| self.refuse(&format!("{flag} needs a value")));
        value
            .split(',')
            .map(|x| {
                x.replace('_', "")
                    .parse()
                    .unwrap_or_else(|_| self.refuse(&format!("{flag}: cannot read {x:?}")))
            })
            .collect()
    }
}

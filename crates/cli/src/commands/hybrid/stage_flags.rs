//! The stage flags of `hybrid render`: one `--NAME VALUE` per stage of the hybrid crate's
//! registry (`renderlab_hybrid::stages`), each with the stage's own help.

use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches};
use renderlab_hybrid::stages::{DESCRIPTORS, NAMES};

/// The stage flags of `hybrid render`: `--NAME VALUE` for every stage of the registry, its
/// help the stage's own (what it does, its syntax, its default).
#[derive(Clone, Debug, Default)]
pub struct StageFlags {
    /// The flags given, as (stage name, value).
    pub values: Vec<(&'static str, String)>,
}

impl StageFlags {
    /// The value given for stage `name`, if any.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.values.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_str())
    }
}

impl FromArgMatches for StageFlags {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let values = NAMES.iter().filter_map(|&n| m.get_one::<String>(n).map(|v| (n, v.clone()))).collect();
        Ok(Self { values })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl Args for StageFlags {
    fn augment_args(cmd: Command) -> Command {
        DESCRIPTORS.iter().fold(cmd, |cmd, d| {
            // The value's placeholder is the flag's name in capitals, as clap's derive writes it.
            let value_name: &'static str = Box::leak(d.name.to_uppercase().into_boxed_str());
            cmd.arg(
                Arg::new(d.name)
                    .long(d.name)
                    .value_name(value_name)
                    .action(ArgAction::Set)
                    .help(d.help_text()),
            )
        })
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

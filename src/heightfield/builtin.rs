//! Built-in terrains, made by `heightray generate` and embedded in the binary so that they
//! work from any directory.

use super::{load_bytes, Heightfield, LoadError};

/// A terrain that ships with heightray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Builtin {
    /// Its name, as the command line and scene files (`builtin:NAME`) give it.
    pub name: &'static str,
    /// Suggested z scale (height of the highest sample value).
    pub z_scale: f64,
    png: &'static [u8],
}

/// All built-in terrains; the first is the default.
pub const BUILTINS: [Builtin; 2] = [
    Builtin {
        name: "valley513",
        z_scale: 120.0,
        png: include_bytes!("../../assets/valley513.png"),
    },
    Builtin {
        name: "small49",
        z_scale: 12.0,
        png: include_bytes!("../../assets/small49.png"),
    },
];

impl Builtin {
    /// Looks a built-in terrain up by name.
    pub fn named(name: &str) -> Option<Builtin> {
        BUILTINS.into_iter().find(|b| b.name == name)
    }

    /// Decodes it with its suggested z scale.
    pub fn load(&self) -> Result<Heightfield, LoadError> {
        self.load_scaled(self.z_scale)
    }

    /// Decodes it with the given z scale.
    pub fn load_scaled(&self, z_scale: f64) -> Result<Heightfield, LoadError> {
        load_bytes(self.png, z_scale, self.name)
    }
}

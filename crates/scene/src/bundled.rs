//! The bundled scenes, which the `contopt` command runs by name and prints as templates.

/// A bundled scene: its name and its text (as in `scenes/<name>.toml`).
#[derive(Clone, Copy, Debug)]
pub struct Bundled {
    /// The name, the file's stem.
    pub name: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

macro_rules! bundled {
    ($($name:literal),* $(,)?) => {
        /// The scenes in `scenes/`, built in.
        pub const BUNDLED: &[Bundled] = &[
            $(Bundled { name: $name, text: include_str!(concat!("../../../scenes/", $name, ".toml")) }),*
        ];
    };
}

bundled!(
    "paper-table1",
    "paper-table2",
    "paper-table3",
    "roller",
    "roller-study",
    "roller-envelope",
    "bearing",
    "hertz",
    "flat-punch",
    "punch-on-block",
    "steel-on-aluminium",
    "winkler-bed",
);

/// The bundled scene `name`.
pub fn find(name: &str) -> Option<&'static Bundled> {
    BUNDLED.iter().find(|b| b.name == name)
}

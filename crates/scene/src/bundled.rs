//! The bundled scenes, which the `contopt` command runs by name.

/// The scenes in `scenes/`, built in: `(name, TOML text)`.
pub const BUNDLED: &[(&str, &str)] = &[
    (
        "paper-table1",
        include_str!("../../../scenes/paper-table1.toml"),
    ),
    (
        "paper-table2",
        include_str!("../../../scenes/paper-table2.toml"),
    ),
    (
        "paper-table3",
        include_str!("../../../scenes/paper-table3.toml"),
    ),
    ("roller", include_str!("../../../scenes/roller.toml")),
    (
        "roller-study",
        include_str!("../../../scenes/roller-study.toml"),
    ),
    (
        "roller-envelope",
        include_str!("../../../scenes/roller-envelope.toml"),
    ),
    ("hertz", include_str!("../../../scenes/hertz.toml")),
    (
        "flat-punch",
        include_str!("../../../scenes/flat-punch.toml"),
    ),
    (
        "punch-on-block",
        include_str!("../../../scenes/punch-on-block.toml"),
    ),
    (
        "steel-on-aluminium",
        include_str!("../../../scenes/steel-on-aluminium.toml"),
    ),
];

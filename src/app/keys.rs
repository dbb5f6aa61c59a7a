//! The demo's keys, in one list: the HUD's key panel (H) and `shadowmap demo --help` both
//! show it (the demo's `window_event` and `update` handle them).

/// The keys, as the demo handles them: a key added there belongs here too.
pub const KEYS: &[(&str, &str)] = &[
    ("UP / RIGHT", "raise the light angle (faster while held)"),
    ("DOWN / LEFT", "lower it (0 to 180, about its azimuth)"),
    ("W / S", "move forward / back"),
    ("A / D", "move left / right"),
    ("Z / X", "move down / up"),
    ("right drag", "look around"),
    (
        "1..9, 0, -, =",
        "the scene's steps in order (the chapters: 1 to 12)",
    ),
    ("Backspace", "the scene's own settings"),
    ("M", "each casting light's shadow map, then the scene"),
    ("V", "shadow maps / stencil shadow volumes"),
    ("B", "draw the shadow volumes over the scene"),
    ("C", "tint the cascades"),
    ("K", "cascades: 1, 2, 3, 4, 1, ..."),
    ("G", "caster groups: 1, 2, 3, 4, 1, ..."),
    ("T", "translucent casters: off, solid, osm, fom, off, ..."),
    ("I", "the shadow-map inset (bottom-right)"),
    ("H", "show / hide these keys"),
    (
        "P",
        "show / hide the shadow cache's counters (maps drawn, patched, reused)",
    ),
    ("F12", "save a screenshot (PNG, current folder)"),
    ("ESC", "quit"),
];

/// [`KEYS`] as a table for the terminal.
pub fn keys_help() -> String {
    let width = KEYS.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    let rows: Vec<String> = KEYS
        .iter()
        .map(|(k, d)| format!("  {k:<width$}  {d}"))
        .collect();
    format!("Keys:\n{}", rows.join("\n"))
}

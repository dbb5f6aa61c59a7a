//! The demo's keys, in one list: the HUD's key panel (H) and `shadowmap demo --help` both
//! show it (the demo's `window_event` and `update` handle them).

use winit::keyboard::KeyCode;

/// The number keys: the steps of the scene's list in order, from the first.
pub const STEP_KEYS: [KeyCode; 12] = [
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit4,
    KeyCode::Digit5,
    KeyCode::Digit6,
    KeyCode::Digit7,
    KeyCode::Digit8,
    KeyCode::Digit9,
    KeyCode::Digit0,
    KeyCode::Minus,
    KeyCode::Equal,
];

/// What a key does to the step shown, for a list of `count` steps with step `current`
/// (its index) or the scene's own settings (`None`) shown: `Some(pick)` picks step
/// `pick` (`None`: the scene's own settings), `None` leaves the step alone. N and
/// PageDown walk the whole list and back to the scene's own, Shift+N and PageUp the other
/// way, so every step can be reached however long the list.
pub fn step_key(
    code: KeyCode,
    shift: bool,
    current: Option<usize>,
    count: usize,
) -> Option<Option<usize>> {
    let next = |i: Option<usize>| match i {
        None if count > 0 => Some(0),
        Some(i) if i + 1 < count => Some(i + 1),
        _ => None,
    };
    let before = |i: Option<usize>| match i {
        None => count.checked_sub(1),
        Some(0) => None,
        Some(i) => Some(i - 1),
    };
    match code {
        KeyCode::Backspace => Some(None),
        KeyCode::KeyN if shift => Some(before(current)),
        KeyCode::KeyN | KeyCode::PageDown => Some(next(current)),
        KeyCode::PageUp => Some(before(current)),
        _ => STEP_KEYS
            .iter()
            .position(|k| *k == code)
            .filter(|&i| i < count)
            .map(Some),
    }
}

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
        "the scene's steps 1 to 12, each as `--step` shows it",
    ),
    (
        "N / PageDown",
        "the next step (every step of the list, then the scene's own)",
    ),
    ("Shift+N / PageUp", "the step before"),
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

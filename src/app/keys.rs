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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every list's every step is reached by N from the scene's own settings, and N after
    /// the last goes back to them; Shift+N and PageUp walk back the same way.
    #[test]
    fn every_step_of_every_list_is_reached_from_the_keyboard() {
        for name in shadowmap::Scene::builtin_names() {
            let scene = shadowmap::Scene::load(name).unwrap();
            let count = shadowmap::steps::of(&scene).len();
            let mut seen = Vec::new();
            let mut at = None;
            for _ in 0..count {
                at = step_key(KeyCode::KeyN, false, at, count).unwrap();
                seen.push(at.unwrap_or_else(|| panic!("{name}: N left the list early")));
            }
            assert_eq!(seen, (0..count).collect::<Vec<_>>(), "{name}");
            assert_eq!(step_key(KeyCode::PageDown, false, at, count), Some(None));
            let mut back = Vec::new();
            let mut at = None;
            for (i, key) in (0..count).map(|i| (i, [KeyCode::KeyN, KeyCode::PageUp][i % 2])) {
                at = step_key(key, key == KeyCode::KeyN, at, count).unwrap();
                back.push(at.unwrap_or_else(|| panic!("{name}: back {i} left the list")));
            }
            assert_eq!(back, (0..count).rev().collect::<Vec<_>>(), "{name}");
        }
    }

    #[test]
    fn the_number_keys_pick_the_first_twelve_steps_and_backspace_the_scene() {
        // The chapters' 13 steps: the number keys reach 12, N the thirteenth.
        assert_eq!(step_key(KeyCode::Digit1, false, None, 13), Some(Some(0)));
        assert_eq!(step_key(KeyCode::Equal, false, None, 13), Some(Some(11)));
        assert_eq!(step_key(KeyCode::KeyN, false, Some(11), 13), Some(Some(12)));
        // A key past a short list's end does nothing; Backspace leaves any step.
        assert_eq!(step_key(KeyCode::Digit9, false, None, 5), None);
        assert_eq!(step_key(KeyCode::Backspace, false, Some(3), 5), Some(None));
        assert_eq!(step_key(KeyCode::KeyM, false, Some(3), 5), None);
    }

    #[test]
    fn the_key_table_names_the_walking_keys() {
        let help = keys_help();
        for key in ["N / PageDown", "Shift+N / PageUp", "Backspace"] {
            assert!(help.contains(key), "{help}");
        }
    }
}

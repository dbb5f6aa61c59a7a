//! "Did you mean": the nearest of the names a value could have been, by edit distance, for
//! every message that refuses a name (scenes, steps, scene-file keys and values, flags'
//! values).

/// The candidate nearest to `word` when it is near enough to be a slip of the keyboard: at
/// most one edit (a swap of neighbours counts as one) for a word of up to five letters, two
/// up to eight, three beyond. Case is ignored; the first of equally near candidates wins.
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let word = word.to_lowercase();
    let allowed = match word.chars().count() {
        0 => return None,
        1..=5 => 1,
        6..=8 => 2,
        _ => 3,
    };
    candidates
        .into_iter()
        .map(|c| (strsim::osa_distance(&word, &c.to_lowercase()), c))
        .filter(|(d, _)| *d <= allowed)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// " (did you mean `x`?)" for a message, or nothing when no candidate is near.
pub fn hint<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    did_you_mean(word, candidates).map_or(String::new(), |c| format!(" (did you mean `{c}`?)"))
}

#[cfg(test)]
mod tests {
    use super::did_you_mean;

    #[test]
    fn slips_find_their_word_and_strangers_find_none() {
        let scenes = ["dummy", "learnopengl", "slides", "smoke"];
        assert_eq!(did_you_mean("dumy", scenes), Some("dummy"));
        assert_eq!(did_you_mean("Smoek", scenes), Some("smoke"));
        assert_eq!(did_you_mean("learnopngl", scenes), Some("learnopengl"));
        assert_eq!(did_you_mean("castle", scenes), None);
        assert_eq!(did_you_mean("", scenes), None);
        let steps = ["pcf", "pcss", "bias", "no-bias"];
        assert_eq!(did_you_mean("pfc", steps), Some("pcf"));
        assert_eq!(
            did_you_mean("mapsize", ["map_size", "max_size"]),
            Some("map_size")
        );
    }
}

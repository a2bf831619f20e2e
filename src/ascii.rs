//! The ASCII spelling of thud's text and figures, one table for every front end: the
//! explorer's `--ascii` screen and exports, and the command line's `--ascii` figures and
//! reports (`θ` → `theta`, `µs` → `us`, `−` → `-`; anything unknown `?`).

/// The ASCII spelling of a non-ASCII character in text, if it has one.
pub fn word(c: char) -> Option<&'static str> {
    Some(match c {
        'θ' => "theta",
        'µ' | 'μ' => "u",
        'τ' => "tau",
        'λ' => "lambda",
        'κ' => "kappa",
        'ρ' => "rho",
        'α' => "alpha",
        'δ' => "delta",
        'Δ' => "delta ",
        'ν' => "nu",
        'π' => "pi",
        '§' => "section ",
        'ω' => "omega",
        'Ω' => "Omega",
        'β' => "beta",
        'γ' => "gamma",
        'ε' => "eps",
        'ζ' => "zeta",
        'η' => "eta",
        'σ' => "sigma",
        'φ' => "phi",
        '█' | '■' => "#",
        '┈' | '╌' => "-",
        '▲' => "^",
        '▼' => "v",
        '✓' => "ok",
        '·' => "*",
        '—' | '–' | '−' => "-",
        '×' => "x",
        '÷' => "/",
        '≥' => ">=",
        '≤' => "<=",
        '≈' | '≃' | '∼' => "~",
        '±' => "+/-",
        '≠' => "!=",
        '∞' => "inf",
        '√' => "sqrt",
        '○' | '◇' => "o",
        '●' | '◆' => "o",
        '…' | '⋯' => "...",
        '→' => "->",
        '←' => "<-",
        '↑' => "^",
        '↓' => "v",
        '°' => "deg",
        '▶' => ">",
        '✗' => "x",
        '²' => "^2",
        '³' => "^3",
        '½' => "1/2",
        '•' => "o",
        '’' | '‘' => "'",
        '“' | '”' => "\"",
        '│' => "|",
        '─' => "-",
        '░' => ":",
        '┌' | '┐' | '└' | '┘' | '┼' | '┬' | '┴' | '├' | '┤' => "+",
        _ => return None,
    })
}

/// An SVG document of thud's with every character beyond ASCII spelled as [`fold`] spells it
/// (`−` → `-`, `²` → `^2`, `θ` → `theta`), escaped for XML (`≤` → `&lt;=`): what `--ascii`
/// writes, from the command line and from the explorer's export key alike.
#[must_use]
pub fn figure(svg: String) -> String {
    if svg.is_ascii() {
        return svg;
    }
    let mut out = String::with_capacity(svg.len());
    let mut buf = [0u8; 4];
    for c in svg.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            out += &crate::export::svg::escape(&fold(c.encode_utf8(&mut buf)));
        }
    }
    out
}

/// `s` in ASCII: known symbols spelled out (`θ` → `theta`, `µs` → `us`), anything else `?`.
pub fn fold(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            out.push_str(word(c).unwrap_or("?"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_spells_what_it_can_instead_of_a_question_mark() {
        let folded = fold("±0.02 dB, e ≈ 0.5, N ≠ 1, ∞, ○○ none ●● damper, cut…");
        assert_eq!(folded, "+/-0.02 dB, e ~ 0.5, N != 1, inf, oo none oo damper, cut...");
        assert!(!folded.contains('?'));
    }

    #[test]
    fn fold_spells_units_and_symbols_in_ascii() {
        assert_eq!(fold("θ 45.0° τ@U0max 229 µs N·s/m"), "theta 45.0deg tau@U0max 229 us N*s/m");
        assert_eq!(fold("a — b → c ≥ d"), "a - b -> c >= d");
        assert!(fold("日本").is_ascii());
    }
}

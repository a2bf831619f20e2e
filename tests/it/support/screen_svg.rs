//! A terminal frame as an SVG picture: ratatui's `Buffer` (what the explorer draws on the
//! `TestBackend`) as monospace text cells with their foreground and background colours, the
//! terminal's default colours those of a dark terminal. Each run of cells of one look is one
//! `<text>` stretched to its cells' width (`textLength`), so columns line up in any monospace
//! font; each run of one background is one `<rect>`.

use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use std::fmt::Write as _;

/// One cell's width and height (px), and the text's size.
const CELL_W: f64 = 8.4;
const CELL_H: f64 = 17.0;
const FONT: f64 = 14.0;
/// The terminal's own foreground and background (a dark theme).
const DEFAULT_FG: &str = "#d0d0d0";
const DEFAULT_BG: &str = "#1d1f21";

/// `c` as `#rrggbb`; `default` for the terminal's own colour.
fn hex(c: Color, default: &str) -> String {
    let (r, g, b) = match c {
        Color::Reset => return default.to_string(),
        Color::Rgb(r, g, b) => (r, g, b),
        Color::Indexed(i) if i >= 232 => {
            let v = 8 + 10 * (i - 232);
            (v, v, v)
        }
        Color::Indexed(i) if i >= 16 => {
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let i = i - 16;
            (level(i / 36), level((i / 6) % 6), level(i % 6))
        }
        other => thud::tui::theme::XTERM_RGB[usize::from(thud::tui::theme::ansi_index(other).unwrap_or(7))],
    };
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// How one cell looks: (foreground, background, bold, dim).
fn look(buf: &Buffer, x: u16, y: u16) -> (String, String, bool, bool) {
    let cell = &buf[(x, y)];
    let mods = cell.modifier;
    let (mut fg, mut bg) = (hex(cell.fg, DEFAULT_FG), hex(cell.bg, DEFAULT_BG));
    if mods.contains(Modifier::REVERSED) {
        std::mem::swap(&mut fg, &mut bg);
    }
    (fg, bg, mods.contains(Modifier::BOLD), mods.contains(Modifier::DIM))
}

/// The frame `buf` as an SVG document titled `title`.
pub fn buffer_svg(buf: &Buffer, title: &str) -> String {
    let area = buf.area;
    let (w, h) = (f64::from(area.width) * CELL_W, f64::from(area.height) * CELL_H);
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.1} {h:.1}\" \
         font-family=\"'DejaVu Sans Mono', Menlo, Consolas, monospace\" font-size=\"{FONT}\">\n\
         <title>{}</title>\n<rect width=\"100%\" height=\"100%\" fill=\"{DEFAULT_BG}\"/>\n",
        escape(title)
    );
    for y in 0..area.height {
        let top = f64::from(y) * CELL_H;
        // Backgrounds: one rectangle per run of one colour other than the terminal's.
        let mut x = 0;
        while x < area.width {
            let bg = look(buf, x, y).1;
            let start = x;
            while x < area.width && look(buf, x, y).1 == bg {
                x += 1;
            }
            if bg != DEFAULT_BG {
                let _ = writeln!(
                    out,
                    r#"<rect x="{:.1}" y="{top:.1}" width="{:.1}" height="{CELL_H}" fill="{bg}"/>"#,
                    f64::from(start) * CELL_W,
                    f64::from(x - start) * CELL_W
                );
            }
        }
        // Text: one run per foreground, weight and dimness, from its first visible cell to its
        // last (blanks inside a run whatever their colour; a wide glyph's second cell is empty).
        let blank = |x: u16| matches!(buf[(x, y)].symbol(), " " | "");
        let mut x = 0;
        while x < area.width {
            if blank(x) {
                x += 1;
                continue;
            }
            let (fg, _, bold, dim) = look(buf, x, y);
            let (start, mut end, mut text) = (x, x, String::new());
            let same = |x: u16| {
                let l = look(buf, x, y);
                l.0 == fg && l.2 == bold && l.3 == dim
            };
            while x < area.width && (blank(x) || same(x)) {
                text.push_str(buf[(x, y)].symbol());
                x += 1;
                if !blank(x - 1) {
                    end = x;
                }
            }
            let body = text.trim_end();
            let _ = writeln!(
                out,
                r#"<text x="{:.1}" y="{:.1}" fill="{fg}"{}{} textLength="{:.1}" lengthAdjust="spacingAndGlyphs" xml:space="preserve">{}</text>"#,
                f64::from(start) * CELL_W,
                top + CELL_H * 0.78,
                if bold { r#" font-weight="bold""# } else { "" },
                if dim { r#" opacity="0.6""# } else { "" },
                f64::from(end - start) * CELL_W,
                escape(body)
            );
        }
    }
    out.push_str("</svg>\n");
    out
}

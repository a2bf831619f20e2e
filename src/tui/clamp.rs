//! A terminal larger than the explorer can draw: the backend wrapper [`Clamped`] reports at
//! most [`MAX_COLS`] × [`MAX_ROWS`], so ratatui's two screen buffers stay small and the
//! explorer draws into the top-left corner of a larger terminal.
//!
//! ratatui allocates a cell for every position of the terminal's reported size, twice (the
//! frame and the previous one): at 65535 × 65535 that is 4.3 billion cells of some 40 bytes
//! each, and the allocation aborts the process with the terminal in raw mode. Any terminal a
//! person can read fits inside the caps (a 4K screen at the smallest readable font is about
//! 640 × 180 cells).

use ratatui::backend::{Backend, ClearType, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};

/// Most columns drawn.
pub const MAX_COLS: u16 = 800;
/// Most rows drawn.
pub const MAX_ROWS: u16 = 300;

/// `size` held to [`MAX_COLS`] × [`MAX_ROWS`].
pub fn clamp(size: Size) -> Size {
    Size { width: size.width.min(MAX_COLS), height: size.height.min(MAX_ROWS) }
}

/// A backend whose size is clamped ([`clamp`]); everything else is `B`'s.
#[derive(Debug)]
pub struct Clamped<B>(pub B);

impl<B: Backend> Backend for Clamped<B> {
    type Error = B::Error;

    fn draw<'a, I>(&mut self, content: I) -> Result<(), Self::Error>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        self.0.draw(content)
    }

    fn append_lines(&mut self, n: u16) -> Result<(), Self::Error> {
        self.0.append_lines(n)
    }

    fn hide_cursor(&mut self) -> Result<(), Self::Error> {
        self.0.hide_cursor()
    }

    fn show_cursor(&mut self) -> Result<(), Self::Error> {
        self.0.show_cursor()
    }

    fn get_cursor_position(&mut self) -> Result<Position, Self::Error> {
        self.0.get_cursor_position()
    }

    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> Result<(), Self::Error> {
        self.0.set_cursor_position(position)
    }

    fn clear(&mut self) -> Result<(), Self::Error> {
        self.0.clear()
    }

    fn clear_region(&mut self, clear_type: ClearType) -> Result<(), Self::Error> {
        self.0.clear_region(clear_type)
    }

    fn size(&self) -> Result<Size, Self::Error> {
        self.0.size().map(clamp)
    }

    fn window_size(&mut self) -> Result<WindowSize, Self::Error> {
        let w = self.0.window_size()?;
        Ok(WindowSize { columns_rows: clamp(w.columns_rows), pixels: w.pixels })
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        self.0.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A terminal of any reported size that keeps nothing (a TestBackend would allocate it).
    struct Huge(Size);

    impl Backend for Huge {
        type Error = std::io::Error;
        fn draw<'a, I: Iterator<Item = (u16, u16, &'a Cell)>>(&mut self, content: I) -> std::io::Result<()> {
            for (x, y, _) in content {
                assert!(x < MAX_COLS && y < MAX_ROWS, "drew at {x},{y}");
            }
            Ok(())
        }
        fn hide_cursor(&mut self) -> std::io::Result<()> {
            Ok(())
        }
        fn show_cursor(&mut self) -> std::io::Result<()> {
            Ok(())
        }
        fn get_cursor_position(&mut self) -> std::io::Result<Position> {
            Ok(Position::ORIGIN)
        }
        fn set_cursor_position<P: Into<Position>>(&mut self, _: P) -> std::io::Result<()> {
            Ok(())
        }
        fn clear(&mut self) -> std::io::Result<()> {
            Ok(())
        }
        fn clear_region(&mut self, _: ClearType) -> std::io::Result<()> {
            Ok(())
        }
        fn size(&self) -> std::io::Result<Size> {
            Ok(self.0)
        }
        fn window_size(&mut self) -> std::io::Result<WindowSize> {
            Ok(WindowSize { columns_rows: self.0, pixels: Size::new(0, 0) })
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_65535_square_terminal_is_drawn_clamped() {
        let mut term = ratatui::Terminal::new(Clamped(Huge(Size::new(u16::MAX, u16::MAX)))).unwrap();
        let mut app = crate::tui::App::new(crate::design::Design::default(), "default", crate::tui::Palette::default());
        crate::tui::draw(&mut term, &mut app).unwrap();
        assert_eq!(term.get_frame().area().width, MAX_COLS);
        assert_eq!(term.get_frame().area().height, MAX_ROWS);
        // A resize to 6000 × 6000 and back to 80 × 24 follows, clamped.
        term.backend_mut().0 .0 = Size::new(6000, 6000);
        crate::tui::draw(&mut term, &mut app).unwrap();
        assert_eq!(term.get_frame().area().width, MAX_COLS);
        term.backend_mut().0 .0 = Size::new(80, 24);
        crate::tui::draw(&mut term, &mut app).unwrap();
        assert_eq!(term.get_frame().area(), ratatui::layout::Rect::new(0, 0, 80, 24));
    }
}

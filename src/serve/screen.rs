//! A client's screen: ratatui's crossterm backend writing into a buffer that the session's
//! writer hands to the SSH channel, at the size the client said (never the server's own
//! terminal's), and never asking the client anything (a query's reply would arrive as keys).

use ratatui::backend::{Backend, ClearType, CrosstermBackend, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};
use std::cell::RefCell;
use std::io;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

pub struct Screen {
    inner: CrosstermBackend<Sink>,
    sink: Sink,
    size: Size,
}

/// The bytes drawn and not yet sent: shared by the backend, which writes them, and the
/// screen, which takes them (the backend lends no access to its writer).
#[derive(Clone, Default)]
struct Sink(Rc<RefCell<Vec<u8>>>);

impl io::Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Screen {
    pub fn new(width: u16, height: u16) -> Screen {
        let sink = Sink::default();
        Screen {
            inner: CrosstermBackend::new(sink.clone()),
            sink,
            size: Size::new(width, height),
        }
    }

    pub fn resize(&mut self, width: u16, height: u16) {
        self.size = Size::new(width, height);
    }

    /// The bytes written since the last call, if any; `spare` (emptied) is written into
    /// next, so a session draws into the buffers its channel hands back.
    pub fn take(&mut self, spare: &mut Vec<u8>) -> Option<Vec<u8>> {
        let mut sink = self.sink.0.borrow_mut();
        if sink.is_empty() {
            return None;
        }
        spare.clear();
        Some(std::mem::replace(&mut *sink, std::mem::take(spare)))
    }
}

impl io::Write for Screen {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.sink.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Backend for Screen {
    type Error = io::Error;

    fn draw<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        self.inner.draw(content)
    }

    fn hide_cursor(&mut self) -> io::Result<()> {
        self.inner.hide_cursor()
    }

    fn show_cursor(&mut self) -> io::Result<()> {
        self.inner.show_cursor()
    }

    /// Never asked of the client: the full-screen view does not need it.
    fn get_cursor_position(&mut self) -> io::Result<Position> {
        Ok(Position::ORIGIN)
    }

    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> io::Result<()> {
        self.inner.set_cursor_position(position)
    }

    fn clear(&mut self) -> io::Result<()> {
        self.inner.clear()
    }

    fn clear_region(&mut self, clear_type: ClearType) -> io::Result<()> {
        self.inner.clear_region(clear_type)
    }

    fn size(&self) -> io::Result<Size> {
        Ok(self.size)
    }

    fn window_size(&mut self) -> io::Result<WindowSize> {
        Ok(WindowSize {
            columns_rows: self.size,
            pixels: Size::default(),
        })
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// The client's window size, the latest one told: a storm of window changes is one message
/// and one layout a frame, not one each (each cost ~0.9 ms of a core).
pub struct Window {
    /// Columns in the high half, rows in the low.
    latest: AtomicU32,
    /// An `In::Resize` is on its way and not yet read.
    told: AtomicBool,
}

impl Window {
    pub fn new(width: u16, height: u16) -> Window {
        Window {
            latest: AtomicU32::new(pack(width, height)),
            told: AtomicBool::new(false),
        }
    }

    /// Keeps `width` × `height` as the latest; whether the session must be told.
    pub fn set(&self, width: u16, height: u16) -> bool {
        self.latest.store(pack(width, height), Ordering::Release);
        !self.told.swap(true, Ordering::AcqRel)
    }

    /// The latest size; the next change tells the session again.
    pub fn take(&self) -> (u16, u16) {
        self.told.store(false, Ordering::Release);
        let packed = self.latest.load(Ordering::Acquire);
        ((packed >> 16) as u16, packed as u16)
    }
}

fn pack(width: u16, height: u16) -> u32 {
    u32::from(width) << 16 | u32::from(height)
}

#[cfg(test)]
mod tests {
    use super::Screen;
    use std::io::Write;

    /// A frame's bytes go out, and the spare handed in is written into next: once the
    /// channel hands buffers back, no frame makes one.
    #[test]
    fn take_hands_out_the_bytes_and_writes_into_the_spare() {
        let mut screen = Screen::new(80, 24);
        let mut spare = Vec::new();
        assert_eq!(
            screen.take(&mut spare),
            None,
            "nothing drawn, nothing to send"
        );
        screen.write_all(b"first").unwrap();
        let mut back = screen.take(&mut spare).unwrap();
        assert_eq!(back, b"first");
        // The channel hands the first frame's buffer back: the frame after next is drawn in it.
        let reused = back.as_ptr();
        screen.write_all(b"second").unwrap();
        assert_eq!(screen.take(&mut back).unwrap(), b"second");
        assert!(back.is_empty());
        screen.write_all(b"third").unwrap();
        let third = screen.take(&mut Vec::new()).unwrap();
        assert_eq!((third.as_slice(), third.as_ptr()), (&b"third"[..], reused));
    }
}

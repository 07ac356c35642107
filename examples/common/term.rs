//! The terminal loop the animated examples share: an alternate screen restored however the
//! example ends, and a frame wait that returns early on `q`, Esc or Ctrl-C.
#![allow(dead_code)]

use std::io::{self, IsTerminal, Write};
use std::time::Instant;

use crossterm::event::{self, Event, KeyCode, KeyEvent, KeyModifiers};
use crossterm::{cursor, execute, queue, style, terminal};

/// The alternate screen, left on drop.
pub struct Screen;

impl Screen {
    pub fn enter() -> io::Result<Screen> {
        terminal::enable_raw_mode()?;
        execute!(io::stdout(), terminal::EnterAlternateScreen, cursor::Hide)?;
        Ok(Screen)
    }

    /// Draws `lines` from the top left, each cleared to its end.
    pub fn show(&self, lines: impl IntoIterator<Item = String>) -> io::Result<()> {
        let mut out = io::stdout();
        queue!(out, cursor::MoveTo(0, 0))?;
        for line in lines {
            queue!(
                out,
                style::Print(line),
                terminal::Clear(terminal::ClearType::UntilNewLine),
                style::Print("\r\n")
            )?;
        }
        out.flush()
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        let _ = execute!(io::stdout(), cursor::Show, terminal::LeaveAlternateScreen);
        let _ = terminal::disable_raw_mode();
    }
}

/// Waits until `deadline`; `true` when the user asked to quit (`q`, Esc or Ctrl-C).
pub fn wants_to_quit(deadline: Instant) -> io::Result<bool> {
    while let Some(left) = deadline.checked_duration_since(Instant::now()) {
        if !event::poll(left)? {
            break;
        }
        if let Event::Key(KeyEvent {
            code, modifiers, ..
        }) = event::read()?
        {
            let ctrl_c = code == KeyCode::Char('c') && modifiers.contains(KeyModifiers::CONTROL);
            if ctrl_c || code == KeyCode::Char('q') || code == KeyCode::Esc {
                return Ok(true);
            }
        }
    }
    Ok(false)
}

/// An animated example's `main`: `animate` on a terminal (a terminal error ends the example
/// with status 1, its message headed by `name`), otherwise `print` (frames as text, for a
/// pipe or CI).
pub fn play(name: &str, animate: impl FnOnce() -> io::Result<()>, print: impl FnOnce()) {
    if io::stdout().is_terminal() {
        if let Err(e) = animate() {
            eprintln!("{name}: terminal error: {e}");
            std::process::exit(1);
        }
    } else {
        print();
    }
}

//! dunas in a browser: the catapult game and the boat scene compiled to
//! `wasm32-unknown-unknown`, drawn on a `<canvas>` by `web/main.js`.
//!
//! The page calls a few exported functions; no bindings generator. [`start`] picks a scene,
//! [`frame`] steps it one 60 Hz frame and fills the draw list ([`draw_list`] and its length,
//! records described by [`Style`](draw_list::Style)); [`click`] and [`swipe`] are the
//! player's; the rest report the game's state for the page's status line and its browser
//! test. Coordinates are canvas pixels.
//!
//! Build: `cargo build --release -p dunas-web --target wasm32-unknown-unknown`; serve with
//! `node web/serve.mjs` (which builds first).

#[path = "../../examples/common/boats.rs"]
mod boats;
#[path = "../../examples/common/catapult.rs"]
mod catapult;
#[path = "../../examples/common/grapple.rs"]
mod grapple;

pub mod catapult_page;
pub mod draw_list;
pub mod grapple_page;
pub mod harbour;
pub mod view;

use std::cell::RefCell;

use catapult::Penguin;
use catapult_page::CatapultPage;
use draw_list::DrawList;
use grapple_page::GrapplePage;
use harbour::Harbour;

/// Boats in the boat scene.
const BOATS: usize = 9;

/// The scene on the page.
enum Scene {
    Catapult(Box<CatapultPage>),
    Harbour(Box<Harbour>),
    Grapple(Box<GrapplePage>),
}

struct Page {
    scene: Scene,
    list: DrawList,
}

thread_local! {
    static PAGE: RefCell<Page> = RefCell::new(Page {
        scene: Scene::Catapult(Box::new(CatapultPage::new(960.0, 540.0))),
        list: DrawList::default(),
    });
}

fn with_page<T>(f: impl FnOnce(&mut Page) -> T) -> T {
    PAGE.with(|page| f(&mut page.borrow_mut()))
}

fn with_catapult<T: Default>(f: impl FnOnce(&CatapultPage) -> T) -> T {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => f(game),
        _ => T::default(),
    })
}

/// Starts a scene on a `width × height` canvas: 0 the catapult, anything else the boats.
#[unsafe(no_mangle)]
pub extern "C" fn start(scene: u32, width: f32, height: f32) {
    with_page(|page| {
        page.scene = match scene {
            0 => Scene::Catapult(Box::new(CatapultPage::new(width, height))),
            1 => Scene::Harbour(Box::new(Harbour::new(BOATS, width, height))),
            _ => Scene::Grapple(Box::new(GrapplePage::new(width, height))),
        };
        page.list.clear();
    });
}

/// One 60 Hz frame: the scene steps, then draws; returns the draw list's length (numbers).
/// The canvas changed size (pixels): the scene goes on, framed anew.
#[unsafe(no_mangle)]
pub extern "C" fn resize(width: f32, height: f32) {
    with_page(|page| match &mut page.scene {
        Scene::Catapult(game) => game.resize(width, height),
        Scene::Harbour(harbour) => harbour.resize(width, height),
        Scene::Grapple(game) => game.resize(width, height),
    });
}

#[unsafe(no_mangle)]
pub extern "C" fn frame() -> u32 {
    with_page(|page| {
        page.list.clear();
        match &mut page.scene {
            Scene::Catapult(game) => {
                game.step();
                game.draw(&mut page.list);
            }
            Scene::Harbour(harbour) => {
                harbour.step();
                harbour.draw(&mut page.list);
            }
            Scene::Grapple(game) => {
                game.step();
                game.draw(&mut page.list);
            }
        }
        page.list.numbers().len() as u32
    })
}

/// Where the last frame's draw list starts in the module's memory (`f32`s).
#[unsafe(no_mangle)]
pub extern "C" fn draw_list() -> *const f32 {
    with_page(|page| page.list.numbers().as_ptr())
}

/// A click: the catapult lets go (or, once landed, starts again); the boats get a gust.
#[unsafe(no_mangle)]
pub extern "C" fn click() {
    with_page(|page| match &mut page.scene {
        Scene::Catapult(game) => game.click(),
        Scene::Harbour(harbour) => harbour.gust(),
        Scene::Grapple(_) => {}
    });
}

/// A press at a canvas pixel (the grappling hook: a throw to a hook there, or the reel
/// until [`lift`]).
#[unsafe(no_mangle)]
pub extern "C" fn press(x: f32, y: f32) {
    with_page(|page| {
        if let Scene::Grapple(game) = &mut page.scene {
            game.press(x, y);
        }
    });
}

/// The press ended.
#[unsafe(no_mangle)]
pub extern "C" fn lift() {
    with_page(|page| {
        if let Scene::Grapple(game) = &mut page.scene {
            game.lift();
        }
    });
}

/// The grappling hook: the hook the rope hangs from (-1 in another scene).
#[unsafe(no_mangle)]
pub extern "C" fn hook() -> i32 {
    with_page(|page| match &page.scene {
        Scene::Grapple(game) => game.game.hook as i32,
        _ => -1,
    })
}

/// The grappling hook: the rope's length (m), and the largest gap so far between its chain
/// and that length (0.01 is 1%); NaN in another scene.
#[unsafe(no_mangle)]
pub extern "C" fn rope_length() -> f32 {
    with_page(|page| match &page.scene {
        Scene::Grapple(game) => game.game.rope.length(),
        _ => f32::NAN,
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn largest_off() -> f32 {
    with_page(|page| match &page.scene {
        Scene::Grapple(game) => game.game.largest_off,
        _ => f32::NAN,
    })
}

/// The grappling hook: hook `i`'s canvas pixel on `axis` (0 x, 1 y); NaN otherwise.
#[unsafe(no_mangle)]
pub extern "C" fn hook_pixel(i: u32, axis: u32) -> f32 {
    with_page(|page| match &page.scene {
        Scene::Grapple(game) => grapple::HOOKS
            .get(i as usize)
            .map_or(f32::NAN, |&h| game.view.pixel(h)[(axis as usize).min(1)]),
        _ => f32::NAN,
    })
}

/// A stroke of a swipe from `(x0, y0)` to `(x1, y1)`: cuts the catapult's rope where it
/// crosses it as drawn; returns 1 if it cut.
#[unsafe(no_mangle)]
pub extern "C" fn swipe(x0: f32, y0: f32, x1: f32, y1: f32) -> u32 {
    with_page(|page| match &mut page.scene {
        Scene::Catapult(game) => u32::from(game.swipe([x0, y0], [x1, y1])),
        _ => 0,
    })
}

/// Simulated seconds of the scene.
#[unsafe(no_mangle)]
pub extern "C" fn time() -> f32 {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => game.game.time(),
        Scene::Harbour(harbour) => harbour.time(),
        Scene::Grapple(game) => game.game.time(),
    })
}

/// The penguin: 0 on the rope, 1 flying, 2 landed.
#[unsafe(no_mangle)]
pub extern "C" fn penguin() -> u32 {
    with_catapult(|game| match game.game.penguin {
        Penguin::Swinging => 0,
        Penguin::Flying(_) => 1,
        Penguin::Landed { .. } => 2,
    })
}

/// Where the penguin landed (m), NaN before.
#[unsafe(no_mangle)]
pub extern "C" fn landed_x() -> f32 {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => match game.game.penguin {
            Penguin::Landed { x, .. } => x,
            _ => f32::NAN,
        },
        _ => f32::NAN,
    })
}

/// Where the closed-form arc from the penguin's release meets the snow (m), NaN before.
#[unsafe(no_mangle)]
pub extern "C" fn arc_x() -> f32 {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => game.arc_x().unwrap_or(f32::NAN),
        _ => f32::NAN,
    })
}

/// The pieces the catapult's rope is drawn in (1 until it is cut).
#[unsafe(no_mangle)]
pub extern "C" fn pieces() -> u32 {
    with_catapult(|game| game.game.pieces() as u32)
}

/// The rope's largest stretch so far while whole and holding the penguin (0.01 is 1%).
#[unsafe(no_mangle)]
pub extern "C" fn largest_stretch() -> f32 {
    with_catapult(|game| game.game.largest_stretch)
}

/// Frames that ran in slow motion (a step hit its substep cap).
#[unsafe(no_mangle)]
pub extern "C" fn slow_frames() -> u32 {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => game.game.slow_frames,
        Scene::Harbour(harbour) => harbour.slow_frames,
        Scene::Grapple(game) => game.game.slow_frames,
    })
}

/// A canvas coordinate (`axis` 0 for x, 1 for y) of the rope's particle `i` (0 in the hand,
/// 7 under the penguin); NaN for another `i` or outside the catapult.
#[unsafe(no_mangle)]
pub extern "C" fn particle(i: u32, axis: u32) -> f32 {
    with_page(|page| match &page.scene {
        Scene::Catapult(game) => game
            .game
            .rope
            .positions()
            .get(i as usize)
            .map_or(f32::NAN, |&p| game.view.pixel(p)[(axis as usize).min(1)]),
        _ => f32::NAN,
    })
}

/// Runs `frames` frames of a fresh catapult game (stepped and drawn, its penguin let go
/// half-way) away from the page's, for timing; returns the draw list's length at the end.
#[unsafe(no_mangle)]
pub extern "C" fn bench_catapult(frames: u32) -> u32 {
    let mut game = CatapultPage::new(960.0, 540.0);
    let mut list = DrawList::default();
    for k in 0..frames {
        if k == frames / 2 {
            game.click();
        }
        game.step();
        list.clear();
        game.draw(&mut list);
    }
    list.numbers().len() as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_click_lets_go_and_the_penguin_lands_on_the_closed_form_arc() {
        start(0, 960.0, 540.0);
        for _ in 0..150 {
            frame();
        }
        assert_eq!(penguin(), 0);
        click();
        let mut frames = 0;
        while penguin() != 2 && frames < 600 {
            frame();
            frames += 1;
        }
        assert_eq!(penguin(), 2, "the penguin landed");
        assert!(
            (landed_x() - arc_x()).abs() <= 0.01,
            "{} vs {}",
            landed_x(),
            arc_x()
        );
    }

    #[test]
    fn a_swipe_across_the_rope_cuts_it_in_two_drawn_pieces() {
        start(0, 960.0, 540.0);
        for _ in 0..30 {
            frame();
        }
        // Across the rope between particles 3 and 4, 200 pixels long.
        let (a, b) = (
            [particle(3, 0), particle(3, 1)],
            [particle(4, 0), particle(4, 1)],
        );
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        let across = [-dy / len * 100.0, dx / len * 100.0];
        let cut = swipe(
            mid[0] - across[0],
            mid[1] - across[1],
            mid[0] + across[0],
            mid[1] + across[1],
        );
        assert_eq!(cut, 1);
        frame();
        assert_eq!(pieces(), 2);
        let ropes = with_page(|page| {
            page.list
                .records()
                .filter(|&(style, _)| style == draw_list::Style::Rope as u8)
                .count()
        });
        assert_eq!(ropes, 2, "each piece is drawn as its own curve");
    }

    /// The rope's length on the canvas (pixels), along its particles.
    fn rope_on_canvas() -> f32 {
        (0..7)
            .map(|i| {
                let (dx, dy) = (
                    particle(i + 1, 0) - particle(i, 0),
                    particle(i + 1, 1) - particle(i, 1),
                );
                (dx * dx + dy * dy).sqrt()
            })
            .sum()
    }

    #[test]
    fn on_a_phone_held_either_way_the_rope_is_a_fifth_of_the_short_side() {
        start(0, 412.0, 860.0);
        for (width, height) in [(412.0, 860.0), (915.0, 360.0), (412.0, 860.0)] {
            resize(width, height);
            for _ in 0..60 {
                frame();
            }
            let short = f32::min(width, height);
            let rope = rope_on_canvas();
            assert!(rope >= 0.2 * short, "{rope} px on {width}×{height}");
        }
    }

    /// The grappling hook on the page: a press away from the hooks reels in while it lasts;
    /// a press on the next hook, once it is in reach, throws the rope there; the chain
    /// keeps the rope's length within 0.5% throughout.
    #[test]
    fn a_press_reels_in_and_a_tap_on_a_hook_in_reach_throws_to_it() {
        start(2, 412.0, 860.0);
        for _ in 0..30 {
            frame();
        }
        let before = rope_length();
        press(5.0, 850.0);
        for _ in 0..60 {
            frame();
        }
        lift();
        let reeled = rope_length();
        assert!(reeled < before - 3.0, "{before} m, then {reeled} m");
        let mut frames = 0;
        while hook() != 1 && frames < 600 {
            press(hook_pixel(1, 0), hook_pixel(1, 1));
            lift();
            frame();
            frames += 1;
        }
        assert_eq!(hook(), 1, "the rope caught the second hook");
        for _ in 0..120 {
            frame();
        }
        assert_eq!(slow_frames(), 0);
        assert!(largest_off() <= 5e-3, "{}", largest_off());
    }

    #[test]
    fn the_boats_sail_without_slow_motion() {
        start(1, 960.0, 540.0);
        for _ in 0..120 {
            frame();
        }
        click();
        for _ in 0..120 {
            frame();
        }
        assert_eq!(slow_frames(), 0);
        let triangles = with_page(|page| {
            page.list
                .records()
                .filter(|&(style, numbers)| {
                    style == draw_list::Style::Triangle as u8
                        && numbers.iter().all(|n| n.is_finite())
                })
                .count()
        });
        assert_eq!(triangles, BOATS * (12 + 2 * 11 * 11));
    }
}

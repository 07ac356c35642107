//! The crane and the wrecking ball, measured: `cargo run --release -p dunas-rapier`.

use dunas_rapier::scenes;

fn main() {
    let crane = scenes::crane();
    println!(
        "crane: the crate carried {:.2} m; the cable's chain within {:.3}% of its length; the crate's bottom at least {:.3} m above the ground; contacts {:.4} m deep at most",
        crane.carried,
        crane.largest_off * 100.0,
        crane.lowest,
        crane.deepest
    );
    let ball = scenes::wrecking_ball(true);
    let alone = scenes::wrecking_ball(false);
    println!(
        "wrecking ball: {} of 15 boxes knocked; the rope's chain within {:.3}% of its length; the total energy rose {:.3}% of the drop's at most; contacts {:.4} m deep at most, the ball's bottom {:.3} m above the ground at least",
        ball.knocked,
        ball.largest_off * 100.0,
        ball.energy_rise * 100.0,
        ball.deepest,
        ball.lowest
    );
    println!(
        "  with rapier's own rope joint: {} of 15 boxes knocked; the total energy rose {:.3}% of the drop's at most; contacts {:.4} m deep at most",
        alone.knocked,
        alone.energy_rise * 100.0,
        alone.deepest
    );
    let [(dunas, dunas_median), (rapier, rapier_median)] = scenes::wrecking_ball_cost(5);
    println!(
        "wrecking ball frame: {:.1} µs with dunas's rope, {:.1} µs with rapier's rope joint alone: {:.2}× (medians {:.1} and {:.1} µs, {:.2}×; fastest and median of 5 rounds of {} frames)",
        dunas / 1e3,
        rapier / 1e3,
        dunas / rapier,
        dunas_median / 1e3,
        rapier_median / 1e3,
        dunas_median / rapier_median,
        scenes::FRAMES
    );
}

//! Both engines timed on the same rolls and maps in one process.
//!
//! Wall-clock figures on a shared machine drift with the other load, so every comparison
//! alternates its two sides round by round and reports the median of the per-round ratios.

use crate::Engine;
use crate::basin::{Axis, MapSpec, Method, run_map_with};
use crate::batch::{Rolls, RunOptions, stream_batch};
use dicesim_physics::{InitialCondition, Params};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Two sides timed against each other: the medians over the rounds of each side's seconds
/// and of the ratio `time(b) / time(a)` per round.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medians {
    pub a_s: f64,
    pub b_s: f64,
    pub ratio: f64,
}

/// Times `a` and `b` over `rounds` rounds (at least one), alternating which goes first.
pub fn compare(rounds: u64, a: &mut dyn FnMut(), b: &mut dyn FnMut()) -> Medians {
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let (mut ta, mut tb, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..rounds {
        let (x, y) = if round % 2 == 0 {
            let x = time(a);
            (x, time(b))
        } else {
            let y = time(b);
            (time(a), y)
        };
        ta.push(x);
        tb.push(y);
        ratio.push(y / x);
    }
    Medians {
        a_s: median(ta),
        b_s: median(tb),
        ratio: median(ratio),
    }
}

/// The median of `xs` (not empty).
fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// Rolls `rolls` of `params` (valid) on `jobs` threads with `engine`, keeping nothing;
/// returns the steps rolled.
pub fn batch_steps(params: &Params, rolls: &Rolls, jobs: usize, engine: Engine) -> u64 {
    let options = RunOptions { jobs, engine };
    let run = stream_batch(params, rolls, &options, &AtomicBool::new(false), &mut |_| Ok(()))
        .expect("validated parameters and ranges");
    run.summary.steps
}

/// The paper's 200×100 face map at `base`'s height, spin x and y over ±60 rad/s, found by
/// `method` on 2 threads with `engine`; returns its method report.
pub fn paper_map(params: &Params, base: &InitialCondition, method: Method, engine: Engine) -> String {
    let spec = MapSpec {
        x: Axis::parse("initial.angular_velocity.x:-60:60", 200).expect("a valid axis"),
        y: Axis::parse("initial.angular_velocity.y:-60:60", 100).expect("a valid axis"),
        method,
    };
    let options = RunOptions { jobs: 2, engine };
    run_map_with(
        params,
        base,
        &spec,
        &options,
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .expect("a valid map")
    .method_report()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
    }

    #[test]
    fn both_sides_run_once_a_round_in_alternating_order() {
        let order = std::cell::RefCell::new(String::new());
        let m = compare(3, &mut || order.borrow_mut().push('a'), &mut || {
            order.borrow_mut().push('b')
        });
        assert_eq!(order.into_inner(), "abbaab");
        assert!(m.a_s >= 0.0 && m.b_s >= 0.0);
    }
}

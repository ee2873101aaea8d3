//! The plane job against the sweep: every pixel of a row is the sweep's value at the
//! same parameters (outcome and exponent), shards partition the plane and join into the
//! unsharded result, the first pass is a complete coarse picture, and a cancelled plane
//! stops.

use bouncemap_engine::jobs::grid::Axis;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::jobs::picture::STRIDES;
use bouncemap_engine::jobs::{Control, Executor};
use bouncemap_engine::plane::{self, Plane, PlaneJob, PlaneSpec};
use bouncemap_engine::sweep::{self, SweepSpec};
use bouncemap_engine::Table;

fn spec(nx: usize, ny: usize, transient: u64) -> PlaneSpec {
    let mut s = PlaneSpec::new(
        Table::fd(0.1).unwrap(),
        Axis {
            param: SweepParam::Alpha,
            lo: 0.45,
            hi: 0.6,
            n: nx,
        },
        Axis {
            param: SweepParam::D,
            lo: 0.0,
            hi: 1.0,
            n: ny,
        },
        0.45,
        0.8,
    );
    s.transient = transient;
    s
}

#[test]
fn every_row_is_the_sweep_started_near_the_fixed_point() {
    let s = spec(24, 4, 5000);
    let ex = Executor::new(2).unwrap();
    let p = plane::collect(&s, &ex).unwrap();
    assert!(p.complete());
    for j in 0..s.y.n {
        let d = s.y.value(j);
        let mut sw = SweepSpec::new(
            Table::fd(d).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            s.x.lo,
            s.x.hi,
            s.x.n,
        );
        sw.transient = s.transient;
        sw.keep = plane::KEEP;
        sw.initial.near_fixed_point = true;
        sw.lyapunov = true;
        let values = sweep::collect(&sw, &ex).unwrap();
        for (i, v) in values.iter().enumerate() {
            let px = p.get(i, j).unwrap();
            assert_eq!(v.value.to_bits(), s.x.value(i).to_bits());
            assert_eq!(px.outcome, v.outcome, "D = {d}, α = {}", v.value);
            assert_eq!(px.sticking, v.sticking, "D = {d}, α = {}", v.value);
            // The sweep samples an unsettled orbit's exponent over more impacts.
            match (px.lyapunov, v.lyapunov) {
                (Some(a), Some(b)) if a.is_finite() && b.is_finite() => {
                    assert_eq!(a > 1e-3, b > 1e-3, "D = {d}, α = {}: {a} {b}", v.value)
                }
                (a, b) => assert_eq!(a, b, "D = {d}, α = {}", v.value),
            }
        }
    }
}

#[test]
fn shards_join_into_the_whole_plane_and_the_first_pass_covers_it() {
    let whole = spec(19, 11, 2000);
    let ex = Executor::new(2).unwrap();
    let all = plane::collect(&whole, &ex).unwrap();
    let mut joined: Vec<Option<plane::Pixel>> = vec![None; whole.len()];
    for index in 0..3 {
        let mut s = whole.clone();
        s.shard = Shard { index, count: 3 };
        let part = plane::collect(&s, &ex).unwrap();
        assert!(part.complete());
        for (k, px) in part.pixels().iter().enumerate() {
            if let Some(px) = px {
                assert!(s.holds(k));
                assert!(joined[k].is_none());
                joined[k] = Some(*px);
            }
        }
    }
    assert_eq!(joined, all.pixels());

    // After the first pass alone every pixel has a preview: its block's corner.
    let job = PlaneJob::new(whole.clone()).unwrap();
    let mut first = Plane::new(&whole);
    ex.run(job, &Control::new(), |b| {
        if b.pass == 0 {
            first.absorb(b.data)
        }
    });
    let s0 = STRIDES[0];
    for j in 0..whole.y.n {
        for i in 0..whole.x.n {
            assert_eq!(first.get(i, j).is_some(), i % s0 == 0 && j % s0 == 0);
            assert_eq!(
                first.preview(i, j),
                all.get(i - i % s0, j - j % s0),
                "({i}, {j})"
            );
        }
    }
}

#[test]
fn a_cancelled_plane_stops() {
    let s = spec(200, 100, 1_000_000);
    let ex = Executor::new(2).unwrap();
    let control = Control::new();
    let handle = ex.start(PlaneJob::new(s).unwrap(), &control);
    std::thread::sleep(std::time::Duration::from_millis(50));
    let t = std::time::Instant::now();
    control.cancel();
    let summary = handle.wait();
    assert!(summary.cancelled);
    assert!(
        t.elapsed() < std::time::Duration::from_millis(500),
        "{:?}",
        t.elapsed()
    );
}

//! Ranks as threads of one process: the distributed render equals the single-process
//! render bit for bit (images, classes, maps, counters) whatever the number of ranks,
//! threads and the balancing settings; load balancing moves work to ranks that start with
//! none; a rank that dies is reported, in bounded time, instead of being waited for.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use beam_cluster::{Error, Fault, Initial, RankOptions, Settings, render_local, render_local_with};
use beam_trace::{NoProgress, Scene, render};

fn small(mut scene: Scene, w: u32, h: u32) -> Scene {
    scene.camera = scene.camera.resized(w, h).expect("a valid size");
    scene
}

fn soft_shadow_scene() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/soft-shadows.toml");
    let mut scene = Scene::load(&path).expect("the scene loads");
    scene.settings.shadow_method = "stochastic:8".parse().expect("a method");
    small(scene, 136, 100)
}

#[test]
fn any_number_of_ranks_renders_the_single_process_image() {
    let scene = small(Scene::default_scene(), 200, 140);
    let alone = render(&scene, &NoProgress).expect("renders").fingerprint();
    for ranks in [1, 2, 3, 4] {
        let (out, report) = render_local(&scene, ranks, &Settings::default()).expect("renders");
        assert_eq!(out.fingerprint(), alone, "{ranks} ranks");
        assert_eq!(report.ranks.len(), ranks);
        let boxes: u64 = report.ranks.iter().map(|r| r.boxes).sum();
        let pixels: u64 = report.ranks.iter().map(|r| r.pixels).sum();
        assert_eq!(pixels, 200 * 140, "{ranks} ranks: every pixel once");
        assert_eq!(report.origins.iter().flatten().sum::<u64>(), boxes);
    }
}

#[test]
fn soft_shadows_on_ranks_with_one_thread_each() {
    let scene = soft_shadow_scene();
    let alone = render(&scene, &NoProgress).expect("renders");
    let (out, _) = render_local_with(&scene, 3, &Settings::default(), &|_| RankOptions {
        threads: 1,
        ..RankOptions::default()
    })
    .expect("renders");
    assert_eq!(out.fingerprint(), alone.fingerprint());
    assert_eq!(out.stats.work(), alone.stats.work());
    // Several render threads per rank, taking boxes from its list concurrently.
    let (out, report) = render_local_with(&scene, 2, &Settings::default(), &|_| RankOptions {
        render_threads: 3,
        threads: 2,
        ..RankOptions::default()
    })
    .expect("renders");
    assert_eq!(out.fingerprint(), alone.fingerprint());
    assert_eq!(report.render_threads, 3);
}

#[test]
fn a_rank_that_starts_with_nothing_gets_work() {
    let scene = small(Scene::default_scene(), 256, 192);
    let alone = render(&scene, &NoProgress).expect("renders").fingerprint();
    for (threshold, fraction) in [(2, 0.4), (1, 0.2), (4, 0.6)] {
        let settings = Settings {
            initial: Initial::OnRank(0),
            threshold,
            fraction,
            ..Settings::default()
        };
        let (out, report) = render_local(&scene, 3, &settings).expect("renders");
        assert_eq!(out.fingerprint(), alone);
        for r in &report.ranks[1..] {
            assert!(r.boxes_received > 0, "{report}");
            assert!(r.boxes > 0, "rank {} rendered nothing:\n{report}", r.rank);
        }
        assert!(report.balanced());
        assert!(report.ranks[0].donations > 0);
        // Every box of the render lies in rank 0's initial part.
        for row in &report.origins {
            assert!(row[1..].iter().all(|&n| n == 0));
        }
    }
}

#[test]
fn without_balancing_each_rank_renders_its_part() {
    let scene = small(Scene::default_scene(), 256, 192);
    let settings = Settings {
        balance: false,
        ..Settings::default()
    };
    let (out, report) = render_local(&scene, 4, &settings).expect("renders");
    assert_eq!(
        out.fingerprint(),
        render(&scene, &NoProgress).expect("renders").fingerprint()
    );
    assert!(!report.balanced());
    for r in &report.ranks {
        assert_eq!(r.requests + r.donations + r.boxes_received, 0);
        // The quadrants of 256 x 192 on the screen boxes' grid of 32 pixels.
        assert_eq!(r.pixels, 128 * 96, "rank {}", r.rank);
    }
}

#[test]
fn a_dead_rank_is_reported_not_waited_for() {
    let scene = small(Scene::default_scene(), 256, 192);
    let settings = Settings {
        timeout: Duration::from_secs(2),
        heartbeat: Duration::from_millis(100),
        ..Settings::default()
    };
    let t0 = Instant::now();
    let err = render_local_with(&scene, 3, &settings, &|_| RankOptions {
        fault: Some(Fault { rank: 1, after: 1 }),
        ..RankOptions::default()
    })
    .expect_err("the render fails");
    let elapsed = t0.elapsed();
    assert!(
        matches!(err, Error::Silent { rank: 1, .. })
            || matches!(&err, Error::Failed { rank: 1, .. }),
        "{err}"
    );
    assert!(elapsed < Duration::from_secs(60), "took {elapsed:?}");
}

#[test]
fn bad_settings_are_refused_by_name() {
    let scene = small(Scene::default_scene(), 64, 64);
    for (settings, name) in [
        (
            Settings {
                fraction: 0.0,
                ..Settings::default()
            },
            "fraction",
        ),
        (
            Settings {
                unit: Some(100),
                ..Settings::default()
            },
            "unit",
        ),
        (
            Settings {
                initial: Initial::OnRank(5),
                ..Settings::default()
            },
            "initial",
        ),
    ] {
        let e = render_local(&scene, 2, &settings)
            .expect_err("refused")
            .to_string();
        assert!(e.contains(name), "{e}");
    }
}

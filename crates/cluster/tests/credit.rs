//! Termination by credit recovery, under every order of events: ranks bisect, render and
//! give away boxes, and messages (donations, rendered boxes) arrive in any order. The
//! collector's credit is the total exactly when no box is left in a list or in transit, and
//! the rendered boxes then cover the screen once.

use beam_cluster::work::{TOTAL_CREDIT, WorkBox, equal_parts, initial_boxes};
use proptest::prelude::*;

/// A message in transit: boxes donated to a rank, or a rendered box to the collector.
enum Transit {
    Donated(usize, Vec<WorkBox>),
    Rendered(WorkBox),
}

/// The state of a simulated cluster: lists, messages in transit, the collector.
struct Sim {
    ranks: usize,
    width: u32,
    lists: Vec<Vec<WorkBox>>,
    transit: Vec<Transit>,
    credit: u64,
    covered: Vec<u8>,
}

impl Sim {
    fn new(ranks: usize, (w, h): (u32, u32)) -> Self {
        Self {
            ranks,
            width: w,
            lists: initial_boxes(&equal_parts(w, h, ranks, 32), ranks),
            transit: Vec::new(),
            credit: 0,
            covered: vec![0; (w * h) as usize],
        }
    }

    fn step(&mut self, action: u8, a: usize, b: usize) {
        let r = a % self.ranks;
        match action % 3 {
            // A rank takes its last box: bisects it, or renders a final one.
            0 => {
                if let Some(bx) = self.lists[r].pop() {
                    if bx.splits(32) {
                        self.lists[r].extend(bx.bisect(32).expect("credit to halve"));
                    } else {
                        self.transit.push(Transit::Rendered(bx));
                    }
                }
            }
            // A rank gives a share of its boxes to another.
            1 => {
                let n = self.lists[r].len() * 2 / 5;
                if n > 0 {
                    let given: Vec<WorkBox> = self.lists[r].drain(..n).collect();
                    self.transit.push(Transit::Donated(b % self.ranks, given));
                }
            }
            // Some message arrives.
            _ => {
                if !self.transit.is_empty() {
                    let k = b % self.transit.len();
                    match self.transit.swap_remove(k) {
                        Transit::Donated(to, boxes) => self.lists[to].extend(boxes),
                        Transit::Rendered(bx) => {
                            self.credit += bx.credit;
                            for (x, y) in bx.rect.pixels() {
                                self.covered[(y * self.width + x) as usize] += 1;
                            }
                        }
                    }
                }
            }
        }
        let open = self.lists.iter().any(|l| !l.is_empty()) || !self.transit.is_empty();
        assert!(self.credit <= TOTAL_CREDIT);
        assert_eq!(self.credit == TOTAL_CREDIT, !open, "credit {}", self.credit);
    }
}

fn simulate(ranks: usize, size: (u32, u32), steps: &[(u8, usize, usize)]) {
    let mut sim = Sim::new(ranks, size);
    for &(action, a, b) in steps {
        sim.step(action, a, b);
    }
    // Then everything to the end, in a fixed order.
    let mut k = 0;
    while sim.credit < TOTAL_CREDIT {
        sim.step(0, k, k);
        sim.step(2, k, 0);
        k += 1;
        assert!(k < 1_000_000, "the render never ends");
    }
    assert!(
        sim.covered.iter().all(|&c| c == 1),
        "every pixel rendered once"
    );
}

proptest! {
    #[test]
    fn credit_is_whole_exactly_when_no_box_is_left(
        ranks in 1usize..6,
        w in 1u32..400,
        h in 1u32..300,
        steps in proptest::collection::vec((any::<u8>(), any::<usize>(), any::<usize>()), 0..400),
    ) {
        simulate(ranks, (w, h), &steps);
    }
}

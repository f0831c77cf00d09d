//! One rank of a distributed render (the thesis's workstation, 7.2.3-7.2.4): a list of
//! screen boxes that a render thread takes from the back, bisecting boxes larger than the
//! final size and rendering final boxes as windows of the pipeline; and the rank's main
//! thread, which alone talks to the others: it asks for boxes when the list runs short,
//! gives a share of its boxes to a rank that asks, sends rendered boxes to rank 0 with their
//! credit, and tells the others it is alive.
//!
//! Rank 0 renders too, gathers every rendered box and knows the render is complete when
//! the credit of every box has come back ([`crate::work`]); it then stops the others and
//! gathers their statistics. A rank silent for longer than the timeout is reported as an
//! error instead of being waited for.

use std::collections::VecDeque;
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use beam_trace::render::{Piece, Pipeline};
use beam_trace::screen::PixelRect;
use beam_trace::window::Window;
use beam_trace::{NoProgress, Progress, RenderOutput};

use crate::error::Error;
use crate::message::Message;
use crate::report::{ClusterReport, RankStats};
use crate::settings::{Initial, Settings};
use crate::work::{TOTAL_CREDIT, WorkBox, equal_parts, initial_boxes};

/// What rank 0 returns: the render, equal bit for bit to one process's, and the cluster's
/// report.
pub struct Gathered {
    /// The render.
    pub output: RenderOutput,
    /// Time and traffic per rank, and who rendered which part.
    pub report: ClusterReport,
}

/// A failure to inject, for tests of failure detection: rank `rank` stops dead, without a
/// word to the others, once it has rendered `after` boxes.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Fault {
    /// The rank that stops.
    pub rank: usize,
    /// After how many rendered boxes.
    pub after: u64,
}

/// The error a rank returns when its injected [`Fault`] strikes.
pub const FAULT_MESSAGE: &str = "stopped by an injected fault";

/// How a rank runs: its render threads and their rayon threads, where its progress goes,
/// the fault to inject.
pub struct RankOptions<'p> {
    /// Threads that take boxes from the rank's list and render them, each a box at a time
    /// (the thesis: one per processor of the workstation; at least 1).
    pub render_threads: usize,
    /// Rayon threads of the pool the render threads share (0: rayon's global pool).
    pub threads: usize,
    /// Rank 0's progress, in pixels rendered.
    pub progress: &'p dyn Progress,
    /// A fault to inject.
    pub fault: Option<Fault>,
    /// When the render started (before the pipeline's set-up).
    pub started: Instant,
}

impl Default for RankOptions<'_> {
    fn default() -> Self {
        Self {
            render_threads: 1,
            threads: 0,
            progress: &NoProgress,
            fault: None,
            started: Instant::now(),
        }
    }
}

/// The shortest pause of the main thread between polls for messages.
const MIN_PAUSE: Duration = Duration::from_micros(100);

/// The longest pause of the main thread between polls for messages.
const MAX_PAUSE: Duration = Duration::from_millis(2);

/// The list of boxes, shared by the main thread and the render thread.
struct List {
    boxes: VecDeque<WorkBox>,
    stop: bool,
    splits: u64,
}

impl List {
    /// The load of the list: the number of final boxes of side `unit` its boxes hold.
    fn load(&self, unit: u32) -> u64 {
        self.boxes.iter().map(|b| b.units(unit)).sum()
    }

    /// The index of the largest box holding at most `limit` final boxes of side `unit`
    /// (the first of equals).
    fn largest(&self, unit: u32, limit: u64) -> Option<usize> {
        (0..self.boxes.len())
            .filter(|&i| self.boxes[i].units(unit) <= limit)
            .max_by_key(|&i| (self.boxes[i].units(unit), std::cmp::Reverse(i)))
    }
}

struct Shared {
    list: Mutex<List>,
    wake: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, List> {
        self.list.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// What the render thread tells the main thread.
enum Event {
    Rendered(WorkBox, Box<Piece>),
    Failed(String),
}

/// The render threads' own figures.
#[derive(Default)]
struct RenderTimes {
    busy: Duration,
    idle: Duration,
    last_box: Duration,
}

impl RenderTimes {
    /// Adds another thread's times (the latest last box).
    fn add(&mut self, o: &RenderTimes) {
        self.busy += o.busy;
        self.idle += o.idle;
        self.last_box = self.last_box.max(o.last_box);
    }
}

/// A render thread: takes boxes from the back of the list until told to stop.
fn render_thread(
    shared: &Shared,
    pipeline: &Pipeline<'_>,
    (grid, unit, pool, started): (u32, u32, Option<&rayon::ThreadPool>, Instant),
    events: &Sender<Event>,
) -> RenderTimes {
    let mut times = RenderTimes::default();
    let (width, height) = pipeline.full_window().image_size();
    loop {
        let waited = Instant::now();
        let next = {
            let mut list = shared.lock();
            loop {
                if list.stop {
                    times.idle += waited.elapsed();
                    return times;
                }
                match list.boxes.pop_back() {
                    Some(b) if b.splits(unit) => match b.bisect(grid) {
                        Ok([first, second]) => {
                            list.boxes.push_back(second);
                            list.boxes.push_back(first);
                            list.splits += 1;
                        }
                        Err(e) => {
                            let _ = events.send(Event::Failed(e.to_string()));
                            return times;
                        }
                    },
                    Some(b) => break b,
                    None => {
                        list = shared
                            .wake
                            .wait(list)
                            .unwrap_or_else(PoisonError::into_inner);
                    }
                }
            }
        };
        times.idle += waited.elapsed();
        let t0 = Instant::now();
        let render = || {
            Window::new(next.rect, width, height).and_then(|w| match pool {
                Some(pool) => pool.install(|| pipeline.render(&w, &NoProgress)),
                None => pipeline.render(&w, &NoProgress),
            })
        };
        // A panic in the render is this rank's failure, reported like an error: its box's
        // credit would never come back, and the others would wait for it.
        let piece =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(render)).unwrap_or_else(|_| {
                Err(beam_trace::Error::Data(format!(
                    "the render of box {:?} panicked",
                    next.rect
                )))
            });
        times.busy += t0.elapsed();
        times.last_box = started.elapsed();
        let event = match piece {
            Ok(p) => Event::Rendered(next, Box::new(p)),
            Err(e) => Event::Failed(e.to_string()),
        };
        if events.send(event).is_err() {
            return times;
        }
    }
}

/// Runs this process's rank of a distributed render of `pipeline`'s scene over
/// `transport`: rank 0 returns the render and the report, the others `None` once rank 0
/// has every box.
///
/// # Errors
///
/// [`Error::Silent`] when a rank this one waits on sends nothing for the timeout;
/// [`Error::Failed`] when another rank reports a failure; a render or transport error of
/// this rank (which it also reports to the others).
pub fn run_rank(
    transport: &dyn crate::transport::Transport,
    pipeline: &Pipeline<'_>,
    settings: &Settings,
    options: &RankOptions<'_>,
) -> Result<Option<Gathered>, Error> {
    let (rank, size) = (transport.rank(), transport.size());
    let grid = pipeline.grid();
    settings.check(size, grid)?;
    let unit = settings.unit(grid);
    let (width, height) = pipeline.full_window().image_size();
    let mut lists = match settings.initial {
        Initial::Equal => initial_boxes(&equal_parts(width, height, size, grid), size),
        Initial::OnRank(r) => {
            let mut lists = vec![Vec::new(); size];
            lists[r].push(WorkBox {
                rect: PixelRect {
                    x0: 0,
                    y0: 0,
                    x1: width,
                    y1: height,
                },
                credit: TOTAL_CREDIT,
                origin: r as u32,
            });
            lists
        }
    };
    let shared = Shared {
        list: Mutex::new(List {
            boxes: std::mem::take(&mut lists[rank]).into(),
            stop: false,
            splits: 0,
        }),
        wake: Condvar::new(),
    };
    let pool = (options.threads > 0)
        .then(|| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(options.threads)
                .build()
        })
        .transpose()
        .map_err(|e| Error::Setting {
            name: "threads",
            message: e.to_string(),
        })?;
    let (events_tx, events) = channel();
    std::thread::scope(|scope| {
        let workers: Vec<_> = (0..options.render_threads.max(1))
            .map(|_| {
                let shared = &shared;
                let tx = events_tx.clone();
                let cfg = (grid, unit, pool.as_ref(), options.started);
                scope.spawn(move || render_thread(shared, pipeline, cfg, &tx))
            })
            .collect();
        drop(events_tx);
        let mut station = Station {
            transport,
            pipeline,
            grid,
            unit,
            settings,
            options,
            shared: &shared,
            stats: RankStats {
                rank,
                ..RankStats::default()
            },
            last_seen: vec![Instant::now(); size],
            gathered: Gathering::new(size, width, height),
        };
        let result = station.run(&events);
        if let Err(e) = &result
            && !matches!(e, Error::Failed { message, .. } if message == FAULT_MESSAGE)
        {
            // Tell the others at once, so that they stop now rather than at their timeout
            // (and before this rank waits for its render thread's current box).
            tell_failure(transport, &e.to_string());
        }
        // Whatever happened, the render thread stops.
        shared.lock().stop = true;
        shared.wake.notify_all();
        let mut times = RenderTimes::default();
        let mut panicked = false;
        for w in workers {
            match w.join() {
                Ok(t) => times.add(&t),
                Err(_) => panicked = true,
            }
        }
        match result {
            Ok(()) if panicked => Err(Error::Failed {
                rank,
                message: "a render thread panicked".into(),
            }),
            Ok(()) => station.finish(times),
            Err(e) => Err(e),
        }
    })
}

/// Tells every other rank that this one failed, and why (sending errors ignored: the
/// others find out by the timeout then).
pub fn tell_failure(transport: &dyn crate::transport::Transport, why: &str) {
    let message = Message::Failed(why.to_string()).encode();
    for peer in (0..transport.size()).filter(|&p| p != transport.rank()) {
        let _ = transport.send(peer, &message);
    }
}

/// What rank 0 collects.
struct Gathering {
    pieces: Vec<Piece>,
    credit: u64,
    origins: Vec<Vec<u64>>,
    origin_pixels: Vec<Vec<u64>>,
    reports: Vec<Option<RankStats>>,
    pixels: u64,
}

impl Gathering {
    fn new(size: usize, width: u32, height: u32) -> Self {
        Self {
            pieces: Vec::new(),
            credit: 0,
            origins: vec![vec![0; size]; size],
            origin_pixels: vec![vec![0; size]; size],
            reports: vec![None; size],
            pixels: u64::from(width) * u64::from(height),
        }
    }

    fn add(&mut self, by: usize, b: &WorkBox, piece: Piece) -> Result<(), Error> {
        let bad = |message: String| Err(Error::Message { from: by, message });
        let o = b.origin as usize;
        if o >= self.origins.len() {
            return bad(format!(
                "a box of rank {o}'s part, of {} ranks",
                self.origins.len()
            ));
        }
        if piece.window.rect() != b.rect {
            return bad(format!(
                "the pixels of {:?} for the box {:?}",
                piece.window.rect(),
                b.rect
            ));
        }
        let credit = self
            .credit
            .checked_add(b.credit)
            .filter(|&c| c <= TOTAL_CREDIT);
        let Some(credit) = credit else {
            return bad(format!(
                "a box whose credit {} takes the render's past the total (a box counted twice)",
                b.credit
            ));
        };
        self.credit = credit;
        self.origins[by][o] += 1;
        self.origin_pixels[by][o] += b.rect.area();
        self.pieces.push(piece);
        Ok(())
    }
}

/// The main thread of a rank.
struct Station<'s, 'p> {
    transport: &'s dyn crate::transport::Transport,
    pipeline: &'s Pipeline<'p>,
    /// The pipeline's window grid.
    grid: u32,
    /// The side of the final boxes.
    unit: u32,
    settings: &'s Settings,
    options: &'s RankOptions<'s>,
    shared: &'s Shared,
    stats: RankStats,
    last_seen: Vec<Instant>,
    gathered: Gathering,
}

impl Station<'_, '_> {
    fn rank(&self) -> usize {
        self.transport.rank()
    }

    fn size(&self) -> usize {
        self.transport.size()
    }

    fn send(&mut self, to: usize, m: &Message) -> Result<(), Error> {
        let t0 = Instant::now();
        let bytes = m.encode();
        self.transport.send(to, &bytes)?;
        self.stats.messages += 1;
        self.stats.bytes += bytes.len() as u64;
        self.stats.communication += t0.elapsed();
        Ok(())
    }

    /// The next message, decoded. The time of a poll that finds none is not counted as
    /// communication (on an oversubscribed node MPI yields the core inside the poll, and
    /// the wait is the rank's idle time).
    fn recv(&mut self) -> Result<Option<(usize, Message)>, Error> {
        let t0 = Instant::now();
        let Some((from, bytes)) = self.transport.try_recv()? else {
            return Ok(None);
        };
        if from >= self.size() {
            return Err(Error::Transport(format!("a message from rank {from}")));
        }
        self.last_seen[from] = Instant::now();
        let m = Message::decode(&bytes).map_err(|message| Error::Message { from, message })?;
        self.stats.communication += t0.elapsed();
        Ok(Some((from, m)))
    }

    /// The ranks this one waits on: rank 0 every rank that has not sent its statistics,
    /// the others rank 0.
    fn watched(&self) -> Vec<usize> {
        if self.rank() == 0 {
            (1..self.size())
                .filter(|&r| self.gathered.reports[r].is_none())
                .collect()
        } else {
            vec![0]
        }
    }

    /// Checks that every rank this one waits on has been heard from within the timeout.
    fn check_alive(&self) -> Result<(), Error> {
        for r in self.watched() {
            let silent = self.last_seen[r].elapsed();
            if silent > self.settings.timeout {
                return Err(Error::Silent {
                    rank: r,
                    seconds: silent.as_secs_f64(),
                });
            }
        }
        Ok(())
    }

    /// Gives boxes to `to`, which asked: the configured share of the final boxes the list
    /// holds ([`WorkBox::units`]), the largest boxes that fit in the share first, bisecting
    /// the largest box when none fits.
    fn donate(&mut self, to: usize) -> Result<(), Error> {
        let (grid, unit) = (self.grid, self.unit);
        let given: Vec<WorkBox> = {
            let mut list = self.shared.lock();
            let mut left = (list.load(unit) as f64 * self.settings.fraction).floor() as u64;
            let mut given = Vec::new();
            while left > 0 && !list.boxes.is_empty() {
                if let Some(i) = list.largest(unit, left) {
                    let b = list.boxes.remove(i).expect("an index of the list");
                    left -= b.units(unit);
                    given.push(b);
                    continue;
                }
                // Every box is larger than what is left to give: halve the largest.
                let i = list.largest(unit, u64::MAX).expect("a box in the list");
                if !list.boxes[i].splits(unit) {
                    break;
                }
                let [first, second] = list.boxes[i].bisect(grid)?;
                list.boxes[i] = first;
                list.boxes.insert(i + 1, second);
                list.splits += 1;
            }
            given
        };
        if given.is_empty() {
            self.send(to, &Message::Refuse)
        } else {
            self.stats.donations += 1;
            self.stats.boxes_given += given.len() as u64;
            self.send(to, &Message::Donate(given))
        }
    }

    fn run(&mut self, events: &Receiver<Event>) -> Result<(), Error> {
        let (rank, size) = (self.rank(), self.size());
        let heartbeat = self.settings.heartbeat;
        let mut last_beat = Instant::now()
            .checked_sub(heartbeat)
            .unwrap_or_else(Instant::now);
        let mut asked: Option<usize> = None;
        let mut next_peer = (rank + 1) % size;
        let mut refused_in_a_row = 0;
        let mut quiet_until = Instant::now();
        let mut stopping = false;
        let mut rendered = 0u64;
        // The pause between polls when nothing happened: short after activity, longer while
        // quiet, so that an idle rank costs its node's render threads little.
        let mut pause = MIN_PAUSE;
        if rank == 0 {
            self.options.progress.begin("cluster", self.gathered.pixels);
        }
        loop {
            let mut busy = false;
            // Boxes the render thread finished.
            loop {
                let event = match events.try_recv() {
                    Ok(event) => event,
                    Err(TryRecvError::Empty) => break,
                    // The render thread ends only when told to, or when it panicked.
                    Err(TryRecvError::Disconnected) => {
                        return Err(Error::Failed {
                            rank,
                            message: "the render thread ended (it panicked)".into(),
                        });
                    }
                };
                busy = true;
                match event {
                    Event::Rendered(b, piece) => {
                        rendered += 1;
                        self.stats.boxes += 1;
                        self.stats.pixels += b.rect.area();
                        if rank == 0 {
                            self.options.progress.advance(b.rect.area());
                            self.gathered.add(0, &b, *piece)?;
                        } else {
                            self.send(0, &Message::Done(b, piece))?;
                        }
                        if let Some(f) = self.options.fault
                            && f.rank == rank
                            && rendered >= f.after
                        {
                            return Err(Error::Failed {
                                rank,
                                message: FAULT_MESSAGE.into(),
                            });
                        }
                    }
                    Event::Failed(message) => return Err(Error::Failed { rank, message }),
                }
            }
            // Messages from the others.
            while let Some((from, m)) = self.recv()? {
                busy = true;
                match m {
                    Message::Request if stopping => self.send(from, &Message::Refuse)?,
                    Message::Request => self.donate(from)?,
                    Message::Donate(boxes) => {
                        self.stats.boxes_received += boxes.len() as u64;
                        let mut list = self.shared.lock();
                        list.boxes.extend(boxes);
                        drop(list);
                        self.shared.wake.notify_all();
                        asked = None;
                        refused_in_a_row = 0;
                    }
                    Message::Refuse => {
                        self.stats.refusals += 1;
                        asked = None;
                        refused_in_a_row += 1;
                        if refused_in_a_row >= size - 1 {
                            // Every other rank is short too: wait before the next round.
                            refused_in_a_row = 0;
                            quiet_until = Instant::now() + heartbeat / 8;
                        }
                    }
                    Message::Done(b, piece) if rank == 0 => {
                        self.options.progress.advance(b.rect.area());
                        self.gathered.add(from, &b, *piece)?;
                    }
                    Message::Heartbeat => {}
                    Message::Stop if rank != 0 => return Ok(()),
                    Message::Report(r) if rank == 0 && stopping => {
                        self.gathered.reports[from] = Some(r);
                    }
                    Message::Failed(message) => {
                        return Err(Error::Failed {
                            rank: from,
                            message,
                        });
                    }
                    other => {
                        return Err(Error::Message {
                            from,
                            message: format!("unexpected {other:?} at rank {rank}"),
                        });
                    }
                }
            }
            if rank == 0 {
                if !stopping && self.gathered.credit == TOTAL_CREDIT {
                    // Every box is back: nothing can be in a list or in transit.
                    stopping = true;
                    self.options.progress.end();
                    for peer in 1..size {
                        self.send(peer, &Message::Stop)?;
                    }
                }
                if stopping && self.gathered.reports.iter().skip(1).all(Option::is_some) {
                    return Ok(());
                }
            }
            // Ask for boxes when the list runs short.
            if self.settings.balance && size > 1 && !stopping && asked.is_none() {
                let short = self.shared.lock().load(self.unit) < self.settings.threshold as u64;
                if short && Instant::now() >= quiet_until {
                    // The other ranks in turn.
                    let to = next_peer;
                    next_peer = (next_peer + 1) % size;
                    if next_peer == rank {
                        next_peer = (next_peer + 1) % size;
                    }
                    self.stats.requests += 1;
                    self.send(to, &Message::Request)?;
                    asked = Some(to);
                    busy = true;
                }
            }
            if last_beat.elapsed() >= heartbeat {
                last_beat = Instant::now();
                for peer in self.watched() {
                    self.send(peer, &Message::Heartbeat)?;
                }
            }
            self.check_alive()?;
            if busy {
                pause = MIN_PAUSE;
            } else {
                std::thread::sleep(pause);
                pause = (pause * 2).min(MAX_PAUSE);
            }
        }
    }

    /// After a complete render: rank 0 assembles it, the others send their statistics.
    fn finish(mut self, times: RenderTimes) -> Result<Option<Gathered>, Error> {
        self.stats.busy = times.busy;
        self.stats.idle = times.idle;
        self.stats.last_box = times.last_box;
        self.stats.splits = self.shared.lock().splits;
        if self.rank() != 0 {
            let report = Message::Report(self.stats.clone());
            self.send(0, &report)?;
            return Ok(None);
        }
        let g = self.gathered;
        let mut ranks: Vec<RankStats> = g.reports.into_iter().skip(1).flatten().collect();
        ranks.insert(0, self.stats);
        let setup = self
            .pipeline
            .setup_stats()
            .iter()
            .map(|p| p.time)
            .sum::<Duration>();
        let output = self.pipeline.assemble(g.pieces, self.options.started)?;
        Ok(Some(Gathered {
            report: ClusterReport {
                settings: *self.settings,
                unit: self.unit,
                render_threads: self.options.render_threads.max(1),
                threads: self.options.threads,
                wall: output.stats.total,
                setup,
                ranks,
                origins: g.origins,
                origin_pixels: g.origin_pixels,
            },
            output,
        }))
    }
}

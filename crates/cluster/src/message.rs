//! The messages between ranks (the thesis's requests, donations and results, 7.2.4, with
//! the credit of every box, heartbeats, and the end of the render).

use beam_trace::render::Piece;

use crate::report::RankStats;
use crate::wire::{ReadError, Reader, Writer, read_piece, write_piece};
use crate::work::WorkBox;

/// A message from one rank to another.
#[derive(Clone, Debug, PartialEq)]
pub enum Message {
    /// The sender runs short and asks for boxes.
    Request,
    /// Boxes given in answer to a request, each with its credit.
    Donate(Vec<WorkBox>),
    /// Nothing to give.
    Refuse,
    /// A rendered final box and its pixels, to rank 0 (its credit comes back with it).
    Done(WorkBox, Box<Piece>),
    /// The sender is alive.
    Heartbeat,
    /// From rank 0: every box is rendered; send your statistics and stop.
    Stop,
    /// A rank's statistics, its last message.
    Report(RankStats),
    /// The sender failed: why.
    Failed(String),
}

fn write_box(w: &mut Writer, b: &WorkBox) {
    w.rect(b.rect);
    w.u64(b.credit);
    w.u32(b.origin);
}

fn read_box(r: &mut Reader<'_>) -> Result<WorkBox, ReadError> {
    Ok(WorkBox {
        rect: r.rect("box")?,
        credit: r.u64("credit")?,
        origin: r.u32("origin")?,
    })
}

impl Message {
    /// The message as bytes.
    pub fn encode(&self) -> Vec<u8> {
        let mut w = Writer::default();
        match self {
            Message::Request => w.u8(0),
            Message::Donate(boxes) => {
                w.u8(1);
                w.len(boxes.len());
                boxes.iter().for_each(|b| write_box(&mut w, b));
            }
            Message::Refuse => w.u8(2),
            Message::Done(b, piece) => {
                w.u8(3);
                write_box(&mut w, b);
                write_piece(&mut w, piece);
            }
            Message::Heartbeat => w.u8(4),
            Message::Stop => w.u8(5),
            Message::Report(stats) => {
                w.u8(6);
                stats.write(&mut w);
            }
            Message::Failed(why) => {
                w.u8(7);
                w.str(why);
            }
        }
        w.0
    }

    /// The message `bytes` encode.
    ///
    /// # Errors
    ///
    /// What is wrong with the bytes (an unknown kind, a truncated or overlong message).
    pub fn decode(bytes: &[u8]) -> Result<Message, ReadError> {
        let mut r = Reader::new(bytes);
        let m = match r.u8("message kind")? {
            0 => Message::Request,
            1 => {
                let n = r.len("boxes", 28)?;
                Message::Donate((0..n).map(|_| read_box(&mut r)).collect::<Result<_, _>>()?)
            }
            2 => Message::Refuse,
            3 => Message::Done(read_box(&mut r)?, Box::new(read_piece(&mut r)?)),
            4 => Message::Heartbeat,
            5 => Message::Stop,
            6 => Message::Report(RankStats::read(&mut r)?),
            7 => Message::Failed(r.str("failure")?),
            k => return Err(format!("unknown message kind {k}")),
        };
        r.finish("message")?;
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use beam_trace::screen::PixelRect;

    #[test]
    fn messages_round_trip() {
        let b = WorkBox {
            rect: PixelRect {
                x0: 64,
                y0: 128,
                x1: 200,
                y1: 192,
            },
            credit: 12345,
            origin: 3,
        };
        let stats = RankStats {
            rank: 2,
            busy: std::time::Duration::from_millis(1500),
            idle: std::time::Duration::from_nanos(7),
            last_box: std::time::Duration::from_secs(3),
            boxes: 7,
            pixels: 7168,
            splits: 3,
            requests: 11,
            refusals: 9,
            donations: 2,
            boxes_given: 5,
            boxes_received: 1,
            messages: 40,
            bytes: 99,
            ..RankStats::default()
        };
        for m in [
            Message::Request,
            Message::Donate(vec![b, b]),
            Message::Refuse,
            Message::Heartbeat,
            Message::Stop,
            Message::Report(stats),
            Message::Failed("out of memory".into()),
        ] {
            assert_eq!(Message::decode(&m.encode()).unwrap(), m);
        }
        assert!(Message::decode(&[9]).unwrap_err().contains("kind 9"));
        assert!(Message::decode(&[1, 200, 0, 0, 0, 0, 0, 0, 0]).is_err());
        assert!(Message::decode(&[0, 0]).unwrap_err().contains("left over"));
    }
}

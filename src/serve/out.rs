//! What goes to a client: its frames, paced by the link (a frame is taken once its bytes have
//! gone to a socket that holds little unsent), and the socket's bound on a stalled write.

use super::{In, Out};
use russh::ChannelWriteHalf;
use russh::server::Msg;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};

/// Unsent bytes the kernel may hold for a connection.
pub const UNSENT_MAX: u32 = 4 * 1024;

/// The bytes written to a connection's socket so far, and a wake-up at each write.
#[derive(Default)]
pub struct Flushed {
    bytes: AtomicU64,
    wrote: tokio::sync::Notify,
}

impl Flushed {
    /// Waits until `mark` bytes have been written to the socket.
    async fn reach(&self, mark: u64) {
        loop {
            let wrote = self.wrote.notified();
            tokio::pin!(wrote);
            wrote.as_mut().enable();
            if self.bytes.load(Ordering::Relaxed) >= mark {
                return;
            }
            wrote.await;
        }
    }
}

/// Hands a session's frames to its channel, which takes them as the client's window allows
/// (SSH flow control); a frame counts as taken once as many bytes have gone to the socket, whose
/// unsent bytes are bounded ([`UNSENT_MAX`]): the channel's window (2 MB from OpenSSH) and
/// russh's own queue take frames far faster than a slow link carries them, and its screen fell
/// further and further behind. Each taken frame's buffer is handed back, so the next one may be
/// drawn (into it: see [`In::Sent`]). It ends with the connection (`ended`): a write waiting
/// for window space from a client killed or stalled waits for good in russh, holding this task
/// and its buffers (a class's worth of such left 40 KB behind, round after round).
pub async fn write_out(
    write: ChannelWriteHalf<Msg>,
    mut frames: tokio::sync::mpsc::Receiver<Out>,
    inbox: std::sync::mpsc::Sender<In>,
    mut ended: tokio::sync::watch::Receiver<()>,
    flushed: Arc<Flushed>,
) {
    let writes = async {
        while let Some(out) = frames.recv().await {
            match out {
                Out::Frame(bytes) => {
                    // The socket's bytes are the frame's and more (russh is built without
                    // compression: what is written is never smaller than what was handed).
                    let mark = flushed.bytes.load(Ordering::Relaxed) + bytes.len() as u64;
                    if write.data_bytes(bytes.clone()).await.is_err() {
                        break;
                    }
                    flushed.reach(mark).await;
                    let _ = inbox.send(In::Sent(bytes));
                }
                Out::End(bytes) => {
                    let _ = write.data_bytes(bytes.clone()).await;
                    let _ = inbox.send(In::Sent(bytes));
                    let _ = write.exit_status(0).await;
                    let _ = write.eof().await;
                    let _ = write.close().await;
                    break;
                }
            }
        }
    };
    tokio::select! {
        () = writes => {}
        _ = ended.changed() => {}
    }
}

/// The TCP stream, with a bound on how long a write may wait: a client that never reads
/// (its socket full) fails the connection after [`super::Limits::stall`] instead of holding
/// it for good.
pub struct Guarded {
    tcp: tokio::net::TcpStream,
    stall: Duration,
    waiting: Option<Pin<Box<tokio::time::Sleep>>>,
    flushed: Arc<Flushed>,
}

impl Guarded {
    pub fn new(tcp: tokio::net::TcpStream, stall: Duration, flushed: Arc<Flushed>) -> Guarded {
        Guarded {
            tcp,
            stall,
            waiting: None,
            flushed,
        }
    }
}

impl AsyncRead for Guarded {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.tcp).poll_read(cx, buf)
    }
}

impl AsyncWrite for Guarded {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        match Pin::new(&mut self.tcp).poll_write(cx, buf) {
            Poll::Ready(r) => {
                self.waiting = None;
                if let Ok(n) = r {
                    self.flushed.bytes.fetch_add(n as u64, Ordering::Relaxed);
                    self.flushed.wrote.notify_waiters();
                }
                Poll::Ready(r)
            }
            Poll::Pending => {
                let stall = self.stall;
                let timer = self
                    .waiting
                    .get_or_insert_with(|| Box::pin(tokio::time::sleep(stall)));
                match timer.as_mut().poll(cx) {
                    Poll::Ready(()) => Poll::Ready(Err(std::io::ErrorKind::TimedOut.into())),
                    Poll::Pending => Poll::Pending,
                }
            }
        }
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.tcp).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.tcp).poll_shutdown(cx)
    }
}

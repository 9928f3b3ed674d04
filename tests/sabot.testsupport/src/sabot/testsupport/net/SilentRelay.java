package sabot.testsupport.net;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.List;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;

/**
 * A TCP relay on loopback between a client and a server that can go silent: while silenced it passes nothing in
 * either direction on the connections it carries and closes none of them (no FIN, no RST), as a Wi-Fi dead spot or a
 * broken switch does; a new connection's handshake fails meanwhile (the port is closed). Resumed, it passes again
 * what it held (TCP's retransmissions, once the link is back) and takes new connections on the same port. A side that
 * closes or resets its connection during the silence has given up on what it had in flight: that is never delivered,
 * and the other side's connection is reset at the resumption (the closed socket's answer to its next segment). Daemon
 * threads, a reader and a writer per direction of each connection; {@link #close()} ends them all.
 */
public final class SilentRelay implements AutoCloseable {

    private final int port;
    private final InetSocketAddress target;
    /** The listening socket; closed while silent (guarded by {@link #gate}). */
    private ServerSocket listener;
    private final List<Socket> sockets = new CopyOnWriteArrayList<>();
    private final Object gate = new Object();
    private boolean silent;
    private volatile boolean closed;

    /**
     * @param targetPort the server's port on 127.0.0.1
     */
    public SilentRelay(int targetPort) throws IOException {
        this(new InetSocketAddress(InetAddress.getLoopbackAddress(), targetPort));
    }

    /**
     * @param target the server's address and port (e.g. a federation's ejabberd on 127.0.0.2); the relay listens on
     *               127.0.0.1
     */
    public SilentRelay(InetSocketAddress target) throws IOException {
        this.target = target;
        this.listener = new ServerSocket(0, 16, InetAddress.getLoopbackAddress());
        this.port = listener.getLocalPort();
        startAccepting(listener);
    }

    private void startAccepting(ServerSocket on) {
        Thread acceptor = new Thread(() -> accept(on), "silent-relay-accept");
        acceptor.setDaemon(true);
        acceptor.start();
    }

    /** @return the port clients connect to */
    public int port() {
        return port;
    }

    /**
     * From now on nothing passes, in either direction, on any connection; a new connection's handshake fails (the
     * port is closed: refused at once, where a dead link would let it time out).
     */
    public void silence() throws IOException {
        synchronized (gate) {
            silent = true;
            listener.close();
        }
    }

    /** Passes traffic again, what was held first, and takes new connections on the same port. */
    public void resume() throws IOException {
        synchronized (gate) {
            silent = false;
            gate.notifyAll();
            if (!closed && listener.isClosed()) {
                ServerSocket again = new ServerSocket();
                again.setReuseAddress(true);
                again.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), port), 16);
                listener = again;
                startAccepting(again);
            }
        }
    }

    private void accept(ServerSocket on) {
        while (!closed && !on.isClosed()) {
            try {
                Socket client = on.accept();
                Socket server = new Socket();
                server.connect(target, 5000);
                client.setTcpNoDelay(true);
                server.setTcpNoDelay(true);
                sockets.add(client);
                sockets.add(server);
                pump(client, server, "up");
                pump(server, client, "down");
            } catch (IOException e) {
                if (closed || on.isClosed()) {
                    return;
                }
            }
        }
    }

    /** What a reader hands its writer: bytes, or the end of the sender's stream. */
    private record Chunk(byte[] bytes, int length, boolean end, boolean endDuringSilence) {
    }

    private void pump(Socket from, Socket to, String direction) {
        BlockingQueue<Chunk> queue = new LinkedBlockingQueue<>();
        Thread reader = new Thread(() -> {
            try {
                InputStream in = from.getInputStream();
                while (true) {
                    byte[] buffer = new byte[8192];
                    int n = in.read(buffer);
                    if (n < 0) {
                        break;
                    }
                    queue.add(new Chunk(buffer, n, false, false));
                }
            } catch (IOException e) {
                // reset by the sender, or closed by the relay
            }
            boolean duringSilence;
            synchronized (gate) {
                duringSilence = silent;
            }
            queue.add(new Chunk(null, 0, true, duringSilence));
        }, "silent-relay-" + direction + "-read");
        Thread writer = new Thread(() -> {
            try {
                OutputStream out = to.getOutputStream();
                while (true) {
                    Chunk c = queue.take();
                    awaitPassing();
                    if (queue.stream().anyMatch(Chunk::endDuringSilence) || c.endDuringSilence()) {
                        abort(to); // the sender gave up in the silence: what it had in flight is lost
                        break;
                    }
                    if (c.end()) {
                        break;
                    }
                    out.write(c.bytes(), 0, c.length());
                    out.flush();
                }
            } catch (IOException | InterruptedException e) {
                // the other side or the relay closed
            }
            closeQuietly(to);
            closeQuietly(from);
        }, "silent-relay-" + direction + "-write");
        reader.setDaemon(true);
        writer.setDaemon(true);
        reader.start();
        writer.start();
    }

    /** Closes with a reset (SO_LINGER 0), as a host answers a segment of a connection it no longer has. */
    private static void abort(Socket s) {
        try {
            s.setSoLinger(true, 0);
        } catch (IOException ignored) {
            // closed already
        }
        closeQuietly(s);
    }

    private void awaitPassing() throws InterruptedException {
        synchronized (gate) {
            while (silent && !closed) {
                gate.wait();
            }
        }
    }

    private static void closeQuietly(Socket s) {
        try {
            s.close();
        } catch (IOException ignored) {
            // closing
        }
    }

    @Override
    public void close() {
        synchronized (gate) {
            closed = true;
            silent = false;
            gate.notifyAll();
            try {
                listener.close();
            } catch (IOException ignored) {
                // closing
            }
        }
        sockets.forEach(SilentRelay::closeQuietly);
    }
}

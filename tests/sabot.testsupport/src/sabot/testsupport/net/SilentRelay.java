package sabot.testsupport.net;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * A TCP relay on loopback between a client and a server that can go silent: while silenced it passes nothing in
 * either direction and closes nothing (no FIN, no RST), as a Wi-Fi dead spot or a broken switch does; new connections
 * are accepted and then left silent too. Resumed, it passes again what it held. Daemon threads, one pair per
 * connection; {@link #close()} ends them all.
 */
public final class SilentRelay implements AutoCloseable {

    private final ServerSocket listener;
    private final InetSocketAddress target;
    private final List<Socket> sockets = new CopyOnWriteArrayList<>();
    private final Object gate = new Object();
    private boolean silent;
    private volatile boolean closed;

    /**
     * @param targetPort the server's port on 127.0.0.1
     */
    public SilentRelay(int targetPort) throws IOException {
        this.target = new InetSocketAddress(InetAddress.getLoopbackAddress(), targetPort);
        this.listener = new ServerSocket(0, 16, InetAddress.getLoopbackAddress());
        Thread acceptor = new Thread(this::accept, "silent-relay-accept");
        acceptor.setDaemon(true);
        acceptor.start();
    }

    /** @return the port clients connect to */
    public int port() {
        return listener.getLocalPort();
    }

    /** From now on nothing passes, in either direction, on any connection. */
    public void silence() {
        synchronized (gate) {
            silent = true;
        }
    }

    /** Passes traffic again, what was held first. */
    public void resume() {
        synchronized (gate) {
            silent = false;
            gate.notifyAll();
        }
    }

    private void accept() {
        while (!closed) {
            try {
                Socket client = listener.accept();
                Socket server = new Socket();
                server.connect(target, 5000);
                client.setTcpNoDelay(true);
                server.setTcpNoDelay(true);
                sockets.add(client);
                sockets.add(server);
                pump(client, server, "up");
                pump(server, client, "down");
            } catch (IOException e) {
                if (closed) {
                    return;
                }
            }
        }
    }

    private void pump(Socket from, Socket to, String direction) {
        Thread t = new Thread(() -> {
            byte[] buffer = new byte[8192];
            try {
                InputStream in = from.getInputStream();
                OutputStream out = to.getOutputStream();
                while (true) {
                    awaitPassing();
                    int n = in.read(buffer);
                    if (n < 0) {
                        break;
                    }
                    awaitPassing(); // read just before the silence: held until it ends
                    out.write(buffer, 0, n);
                    out.flush();
                }
            } catch (IOException | InterruptedException e) {
                // the other side or the relay closed
            }
            closeQuietly(to);
            closeQuietly(from);
        }, "silent-relay-" + direction);
        t.setDaemon(true);
        t.start();
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
        closed = true;
        resume();
        try {
            listener.close();
        } catch (IOException ignored) {
            // closing
        }
        sockets.forEach(SilentRelay::closeQuietly);
    }
}

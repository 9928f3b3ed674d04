package sabot.fleet;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.net.SocketAddress;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;

import javax.net.SocketFactory;

/**
 * Plain TCP sockets with TCP_NODELAY. Smack 4.4 never disables Nagle's algorithm; together with the peer's delayed
 * ACK every request/response then stalls ~40 ms on loopback (measured: IQ p50 43.7 ms instead of 0.3 ms).
 * STARTTLS layers on top of this socket, so TLS connections benefit as well.
 * <p>
 * It remembers the last socket it made, so that a link found silent can be {@link #abandonLast() abandoned}: closed at
 * the TCP level (a reset), without the TLS close that closing Smack's TLS socket writes. On a link that comes back,
 * that close would reach the server late, after the session has been resumed on a new connection, and Prosody 0.12
 * then ends the resumed stream (not-well-formed).
 * <p>
 * Made with {@linkplain #NoDelaySocketFactory(List) several servers} (the nodes of a cluster, all on one port, as
 * behind one DNS name with several addresses), its sockets connect to the server now {@linkplain #current() chosen},
 * at the port asked for, whatever address Smack's configuration holds (the first server's); {@link #next()} chooses
 * the next one, e.g. after a failed attempt: a client fails over without a connection object of its own per server.
 */
public final class NoDelaySocketFactory extends SocketFactory {

    private volatile Socket last;
    private final List<String> servers;
    private final AtomicInteger chosen = new AtomicInteger();

    /** Sockets that connect where Smack asks. */
    public NoDelaySocketFactory() {
        this.servers = List.of();
    }

    /**
     * Sockets that connect to one of {@code servers} (host names or addresses, each resolved when connecting), the
     * first until {@link #next()}.
     *
     * @throws IllegalArgumentException when the list is empty
     */
    public NoDelaySocketFactory(List<String> servers) {
        if (servers.isEmpty()) {
            throw new IllegalArgumentException("no server");
        }
        this.servers = List.copyOf(servers);
    }

    /** @return the server the next socket connects to; null when the sockets connect where Smack asks */
    public String current() {
        return servers.isEmpty() ? null : servers.get(Math.floorMod(chosen.get(), servers.size()));
    }

    /** Chooses the next server (after the last, the first again). @return it; null as {@link #current()} */
    public String next() {
        if (servers.isEmpty()) {
            return null;
        }
        return servers.get(Math.floorMod(chosen.incrementAndGet(), servers.size()));
    }

    /** @return how many servers there are to choose from (0: where Smack asks) */
    public int size() {
        return servers.size();
    }

    @Override
    public Socket createSocket() throws IOException {
        Socket socket = servers.isEmpty() ? new Socket() : new ChosenServerSocket(current());
        socket.setTcpNoDelay(true);
        last = socket;
        return socket;
    }

    /** A socket that connects to one server at the port asked for (see the class's comment). */
    private static final class ChosenServerSocket extends Socket {
        private final String server;

        ChosenServerSocket(String server) {
            this.server = server;
        }

        @Override
        public void connect(SocketAddress endpoint, int timeout) throws IOException {
            int port = ((InetSocketAddress) endpoint).getPort();
            super.connect(new InetSocketAddress(InetAddress.getByName(server), port), timeout);
        }
    }

    /** Closes the last socket made with a TCP reset, writing nothing more on it; nothing when there is none. */
    public void abandonLast() {
        Socket socket = last;
        if (socket == null || socket.isClosed()) {
            return;
        }
        try {
            socket.setSoLinger(true, 0);
        } catch (IOException e) {
            // closed meanwhile: the close below is then a no-op
        }
        try {
            socket.close();
        } catch (IOException e) {
            // nothing more to do with a socket being abandoned
        }
    }

    @Override
    public Socket createSocket(String host, int port) throws IOException {
        return configure(new Socket(host, port));
    }

    @Override
    public Socket createSocket(String host, int port, InetAddress localHost, int localPort) throws IOException {
        return configure(new Socket(host, port, localHost, localPort));
    }

    @Override
    public Socket createSocket(InetAddress host, int port) throws IOException {
        return configure(new Socket(host, port));
    }

    @Override
    public Socket createSocket(InetAddress address, int port, InetAddress localAddress, int localPort)
            throws IOException {
        return configure(new Socket(address, port, localAddress, localPort));
    }

    private Socket configure(Socket socket) throws IOException {
        socket.setTcpNoDelay(true);
        last = socket;
        return socket;
    }
}

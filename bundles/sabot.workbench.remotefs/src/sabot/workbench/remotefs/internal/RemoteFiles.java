package sabot.workbench.remotefs.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

import org.eclipse.core.runtime.IProgressMonitor;
import org.eclipse.core.runtime.OperationCanceledException;
import org.eclipse.core.runtime.SubMonitor;

import sabot.controlml.Resources;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.robotview.RobotView;

/**
 * A robot's remote FS through {@link FleetState} ({@code cm.fs.*}, docs/CONTROLML.md section 4): listings page by
 * page, files chunk by chunk with their SHA-256, each step checking the progress monitor so that a transfer can be
 * cancelled between chunks. Blocking: called from jobs, never on the UI thread.
 */
final class RemoteFiles {

    /**
     * Bytes per chunk: the robots' default and largest chunk (the remote FS's {@code maxChunk}); 32 KiB of base64 keep
     * a payload well under ControlML's 64 KiB.
     */
    static final int CHUNK = 32 * 1024;

    private final FleetState fleet;
    private final String robot;

    /** A refusal or failure, with the text for the operator. */
    static final class RemoteFsException extends Exception {
        private static final long serialVersionUID = 1L;

        RemoteFsException(String text) {
            super(text);
        }
    }

    RemoteFiles(FleetState fleet, String robot) {
        this.fleet = fleet;
        this.robot = robot;
    }

    /** @return every entry of a directory ("" is the root), in the robot's order (by name), all pages */
    List<FileEntry> list(String dir, IProgressMonitor monitor) throws RemoteFsException {
        List<FileEntry> all = new ArrayList<>();
        while (true) {
            check(monitor);
            DirectoryListing page = await(fleet.get(robot, Resources.FS_LIST, new FileQuery(dir, all.size(), 0)));
            if (page.entries().isEmpty()) {
                return all;
            }
            all.addAll(page.entries());
        }
    }

    /** Writes a local file to {@code remotePath} in chunks; the robot puts it in place with the last one. */
    void upload(Path local, String remotePath, IProgressMonitor monitor) throws RemoteFsException, IOException {
        long size = Files.size(local);
        SubMonitor progress = SubMonitor.convert(monitor, "Upload " + local.getFileName() + " to " + remotePath,
                units(size));
        try (InputStream in = Files.newInputStream(local)) {
            long offset = 0;
            while (true) {
                check(progress);
                byte[] data = in.readNBytes(CHUNK);
                boolean last = offset + data.length >= size;
                await(fleet.set(robot, Resources.FS_WRITE, new FileChunk(remotePath, offset, data, FileChunk
                        .sha256Hex(data), last)));
                offset += data.length;
                progress.worked(1);
                progress.subTask(offset + " of " + size + " bytes");
                if (last) {
                    return;
                }
            }
        }
    }

    /**
     * Reads {@code remotePath} into {@code local}: into a temporary file beside it first, moved into place when
     * complete, so that a cancelled or refused download leaves no half file.
     *
     * @param size the size the listing gave (for the progress only)
     */
    void download(String remotePath, long size, Path local, IProgressMonitor monitor) throws RemoteFsException,
            IOException {
        SubMonitor progress = SubMonitor.convert(monitor, "Download " + remotePath, units(size));
        Path partial = local.resolveSibling("." + local.getFileName() + ".part");
        boolean done = false;
        try (OutputStream out = Files.newOutputStream(partial)) {
            check(progress);
            long[] received = { 0 };
            // the fleet's chunked read (each chunk's SHA-256 checked by the codec); the sink runs on the fleet's
            // threads, this job waits, each chunk bounded by the fleet's request timeout
            awaitDownload(fleet.download(robot, remotePath, CHUNK, chunk -> {
                check(progress);
                out.write(chunk.data());
                received[0] += chunk.data().length;
                progress.worked(1);
                progress.subTask(received[0] + " of " + size + " bytes");
            }));
            done = true;
        } finally {
            if (!done) {
                Files.deleteIfExists(partial);
            }
        }
        Files.move(partial, local, StandardCopyOption.REPLACE_EXISTING, StandardCopyOption.ATOMIC_MOVE);
    }

    /** Deletes a file or an empty directory. */
    void delete(String remotePath) throws RemoteFsException {
        await(fleet.set(robot, Resources.FS_DELETE, new FileQuery(remotePath, 0, 0)));
    }

    /** @return the path of {@code name} in directory {@code dir} ("" is the root) */
    static String child(String dir, String name) {
        return dir.isEmpty() ? name : dir + "/" + name;
    }

    private static int units(long size) {
        return (int) Math.max(1, (size + CHUNK - 1) / CHUNK);
    }

    private static void check(IProgressMonitor monitor) {
        if (monitor.isCanceled()) {
            throw new OperationCanceledException();
        }
    }

    /** Waits for a whole download: a cancellation or an I/O error of the sink comes back as itself. */
    private static void awaitDownload(CompletableFuture<Void> download) throws RemoteFsException, IOException {
        try {
            download.get();
        } catch (ExecutionException e) {
            if (e.getCause() instanceof OperationCanceledException c) {
                throw c;
            }
            if (e.getCause() instanceof IOException io) {
                throw io;
            }
            throw new RemoteFsException(RobotView.reason(e));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            download.cancel(false);
            throw new OperationCanceledException("interrupted");
        }
    }

    private static <T> T await(CompletableFuture<T> answer) throws RemoteFsException {
        try {
            return answer.get(RobotView.ANSWER_TIMEOUT_S, TimeUnit.SECONDS);
        } catch (ExecutionException e) {
            throw new RemoteFsException(RobotView.reason(e));
        } catch (TimeoutException e) {
            throw new RemoteFsException("no answer within " + RobotView.ANSWER_TIMEOUT_S + " s");
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new OperationCanceledException("interrupted");
        }
    }
}

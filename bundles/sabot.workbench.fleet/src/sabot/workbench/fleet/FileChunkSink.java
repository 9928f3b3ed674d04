package sabot.workbench.fleet;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.controlml.payload.FileChunk;

/** Takes the chunks of a file {@link FleetState#download downloaded} from a robot's remote files, in order. */
@ConsumerType
@FunctionalInterface
public interface FileChunkSink {

    /**
     * @param chunk the next chunk (its SHA-256 already checked, its offset the end of the previous one); the last
     *              one says {@link FileChunk#last()}
     * @throws Exception to stop the download (it then fails with this exception: an I/O error, a cancellation)
     */
    void accept(FileChunk chunk) throws Exception;
}

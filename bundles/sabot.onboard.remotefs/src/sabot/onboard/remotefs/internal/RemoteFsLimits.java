package sabot.onboard.remotefs.internal;

import sabot.controlml.payload.FileChunk;

/**
 * The remote-FS service's limits.
 *
 * @param maxChunk          largest chunk read or written, bytes: 1 to {@value FileChunk#MAX_CHUNK}
 *                          (what one ControlML payload carries)
 * @param maxFileSize       largest file a write may produce, bytes, &ge; 0
 * @param maxListPage       most entries in one {@code cm.fs.list} answer: 1 to {@value #MAX_LIST_PAGE}; a page holds
 *                          fewer when its names would not fit one payload
 * @param maxOpenTransfers  most writes in progress at once; starting one more abandons the one that waited longest
 *                          (its temporary file is deleted), 1 to {@value #MAX_OPEN_TRANSFERS}
 * @param readOnly          true to refuse every write and delete with {@code forbidden}/{@code set-not-permitted}
 */
public record RemoteFsLimits(int maxChunk, long maxFileSize, int maxListPage, int maxOpenTransfers,
        boolean readOnly) {

    /** Most entries a {@code cm.fs.list} answer may carry (the protocol's limit). */
    public static final int MAX_LIST_PAGE = 1024;

    /** Default largest file, bytes: 64 MiB. */
    public static final long DEFAULT_MAX_FILE_SIZE = 64L * 1024 * 1024;
    /** Default entries a page: names of up to 100 plain characters fill one payload. */
    public static final int DEFAULT_LIST_PAGE = 128;
    /** Most writes in progress at once (each holds a temporary file). */
    public static final int MAX_OPEN_TRANSFERS = 1024;
    /** Default writes in progress at once. */
    public static final int DEFAULT_OPEN_TRANSFERS = 16;

    /**
     * 32 KiB chunks ({@link FileChunk#MAX_CHUNK}), files up to {@link #DEFAULT_MAX_FILE_SIZE},
     * {@link #DEFAULT_LIST_PAGE} entries a page, {@link #DEFAULT_OPEN_TRANSFERS} transfers at once, writable.
     */
    public static final RemoteFsLimits DEFAULT = new RemoteFsLimits(FileChunk.MAX_CHUNK, DEFAULT_MAX_FILE_SIZE,
            DEFAULT_LIST_PAGE, DEFAULT_OPEN_TRANSFERS, false);

    public RemoteFsLimits {
        if (maxChunk < 1 || maxChunk > FileChunk.MAX_CHUNK) {
            throw new IllegalArgumentException("maxChunk must be 1.." + FileChunk.MAX_CHUNK
                    + " bytes, was " + maxChunk);
        }
        if (maxFileSize < 0) {
            throw new IllegalArgumentException("maxFileSize must be >= 0, was " + maxFileSize);
        }
        if (maxListPage < 1 || maxListPage > MAX_LIST_PAGE) {
            throw new IllegalArgumentException("maxListPage must be 1.." + MAX_LIST_PAGE + ", was " + maxListPage);
        }
        if (maxOpenTransfers < 1 || maxOpenTransfers > MAX_OPEN_TRANSFERS) {
            throw new IllegalArgumentException("maxOpenTransfers must be 1.." + MAX_OPEN_TRANSFERS + ", was "
                    + maxOpenTransfers);
        }
    }

    /** @return these limits, read-only */
    public RemoteFsLimits asReadOnly() {
        return new RemoteFsLimits(maxChunk, maxFileSize, maxListPage, maxOpenTransfers, true);
    }

    /** @return these limits with another file-size limit */
    public RemoteFsLimits withMaxFileSize(long bytes) {
        return new RemoteFsLimits(maxChunk, bytes, maxListPage, maxOpenTransfers, readOnly);
    }
}

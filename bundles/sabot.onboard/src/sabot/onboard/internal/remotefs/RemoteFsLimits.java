package sabot.onboard.internal.remotefs;

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
 *                          (its temporary file is deleted), &ge; 1
 * @param readOnly          true to refuse every write and delete with {@code forbidden}/{@code set-not-permitted}
 */
public record RemoteFsLimits(int maxChunk, long maxFileSize, int maxListPage, int maxOpenTransfers,
        boolean readOnly) {

    /** Most entries a {@code cm.fs.list} answer may carry (the protocol's limit). */
    public static final int MAX_LIST_PAGE = 1024;

    /**
     * 32 KiB chunks, files up to 64 MiB, 128 entries a page (names of up to 100 plain characters fill it), 16
     * transfers at once, writable.
     */
    public static final RemoteFsLimits DEFAULT = new RemoteFsLimits(FileChunk.MAX_CHUNK,
            64L * 1024 * 1024, 128, 16, false);

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
        if (maxOpenTransfers < 1) {
            throw new IllegalArgumentException("maxOpenTransfers must be >= 1, was " + maxOpenTransfers);
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

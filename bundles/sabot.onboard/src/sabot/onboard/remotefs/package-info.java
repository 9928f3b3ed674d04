/**
 * The robot's remote file system over ControlML ({@code cm.fs.list}, {@code cm.fs.read}, {@code cm.fs.write},
 * {@code cm.fs.delete}): one onboard root, chunked transfers with a SHA-256 per chunk, atomic replacement of files.
 */
package sabot.onboard.remotefs;

package sabot.planner.internal;

import java.lang.ref.Cleaner;
import java.util.Arrays;
import java.util.concurrent.locks.LockSupport;

/**
 * The propagation of {@link LpnNavigationFunction} on two threads, for the whole reachable grid.
 *
 * <p><b>Ownership.</b> The padded grid is cut into bands of {@code 2^bandLog2} consecutive cells (at least four rows),
 * owned alternately by worker 0 and worker 1. A worker writes only the cells it owns, so the stored values need no
 * atomic operations. A cell whose row above or below lies in the other band ("near the boundary") has neighbours of
 * both owners: when its owner lowers it, it also hands the cell with its value to the other worker's <em>halo</em>
 * queue, and the other worker expands it for the neighbours it owns. Halo entries carry the value they were queued
 * with; an entry whose cell has been lowered again since is stale and skipped (its newer entry comes first).
 *
 * <p><b>Order.</b> Each worker has its own ring of Dial buckets (the same widths as the sequential propagation). A
 * worker finishes bucket k (its own cells, sorted by memory band, then its halo entries) only once the other has
 * finished bucket k - 1, so the two never drift more than one bucket apart. Values below bucket k are then final on
 * both sides; but a worker may still write values into bucket k while the other expands it (an update through a much
 * lower corner, the straight diagonal, raises N by less than a bucket over the value expanded). So that results do not
 * depend on timing, a worker never reads the other's cells from the grid: it reads them from a snapshot the other
 * took at the end of bucket k - 1 (two of them, alternating, hold the cells within two rows of a boundary). Every run
 * gives the same bits. The workers stop at the first bucket k that both have passed without anything queued at k or
 * later (each publishes the last bucket it queued into, its own or the other's halo, with the bucket it finished).
 *
 * <p><b>Overlap.</b> Only the cells next to the other band (and its halo entries) read the other's cells. A worker
 * therefore expands the rest of its bucket k before it waits for the other to finish k - 1, and the cells next to the
 * boundary after: their values are final already (the other's updates reach them through halo entries of earlier
 * buckets, expanded in those buckets), and what the early cells read is this worker's own. The wait for the slower
 * worker, 2-3 ms of a 1M-cell computation when the two took turns bucket by bucket, now mostly overlaps with work.
 *
 * <p><b>Versus one thread.</b> N is the same function up to which straight diagonal steps are seen: the sequential
 * method already misses one when both axis cells beside it are expanded after the cell in the same bucket, so N
 * depends on the order within a bucket, and two threads order it differently (the cells next to a boundary last in
 * their bucket, and the other band seen one bucket late). The reached cells are the same. On the benchmark grids
 * (random-1000, maze-1000: no graded costs) every value is the same as on one thread; on a 600 x 520 test grid with
 * graded costs, 6.6 % of the values differ (nine in ten higher), by at most 0.54 % (downstream of cells next to a
 * boundary; 2.7 % by at most 0.03 % before the overlap), both being the costs of real paths; paths meet the same
 * properties (PlannerCompletenessPropertyTest runs on both).
 *
 * <p>The second worker runs on a daemon thread owned by this object, parked between computations; {@link #close}
 * ends it (and a {@link Cleaner} does, should an instance be dropped unclosed). Workers wait for each other by
 * spinning: a computation keeps both cores busy while it lasts.
 */
final class BandedPropagation implements AutoCloseable {

    /** Ends helper threads of instances dropped without {@link #close}. */
    private static final Cleaner CLEANER = Cleaner.create();

    private final Crew crew;
    private final Cleaner.Cleanable cleanable;

    /**
     * @param minBandLog2 log2 of the least ownership band size in padded cells; each run raises it until a band holds
     *                    more than four rows of its grid
     */
    BandedPropagation(float[] halfDensity, float inverseBucketWidth, int bucketMask, int minBandLog2) {
        this.crew = new Crew(halfDensity, inverseBucketWidth, bucketMask, minBandLog2);
        this.cleanable = CLEANER.register(this, crew::close);
    }

    /** @return whether bands of this size work for rows of {@code stride} cells: more than four rows per band */
    static boolean bandsFit(int bandLog2, int stride) {
        return (1L << bandLog2) > 4L * stride + 4;
    }

    /**
     * Expands everything reachable from {@code goals} (padded indices of cells reset to {@link
     * LpnNavigationFunction#UNREACHED}): on return every reachable cell holds its final value with the final flag.
     *
     * @param sortBandLog2 log2 of the memory bands a large bucket is sorted by (as in the sequential propagation)
     * @return the number of cells finalized
     */
    int propagate(int[] potential, byte[] costs, int stride, int[] goals, int sortBandLog2) {
        return crew.propagate(potential, costs, stride, goals, sortBandLog2);
    }

    @Override
    public void close() {
        cleanable.clean();
    }

    /** Everything the helper thread touches: it must not refer to the {@link BandedPropagation} the cleaner watches. */
    private static final class Crew {
        final float[] halfDensity;
        final float inverseBucketWidth;
        final int bucketMask;
        final int minBandLog2;
        /** Per run: ownership bands, at least {@link #minBandLog2} and more than four rows. */
        int bandLog2;
        int sortBandLog2;
        final Worker[] workers = new Worker[2];

        int[] potential;
        byte[] costs;
        int stride;
        /** Incremented (after the inputs are set) to start the helper's worker. */
        volatile int generation;
        volatile boolean closed;
        volatile boolean helperFinished = true;
        volatile Throwable helperFailure;
        Thread helper;

        Crew(float[] halfDensity, float inverseBucketWidth, int bucketMask, int minBandLog2) {
            this.halfDensity = halfDensity;
            this.inverseBucketWidth = inverseBucketWidth;
            this.bucketMask = bucketMask;
            this.minBandLog2 = minBandLog2;
            workers[0] = new Worker(this, 0);
            workers[1] = new Worker(this, 1);
            workers[0].meet(workers[1]);
            workers[1].meet(workers[0]);
        }

        int propagate(int[] potential, byte[] costs, int stride, int[] goals, int sortBandLog2) {
            if (closed) {
                throw new IllegalStateException("the two-thread propagation is closed");
            }
            int bands = minBandLog2;
            while (!bandsFit(bands, stride)) {
                bands++;
            }
            this.bandLog2 = bands;
            this.sortBandLog2 = sortBandLog2;
            this.potential = potential;
            this.costs = costs;
            this.stride = stride;
            for (Worker worker : workers) {
                worker.reset(potential.length >>> sortBandLog2);
            }
            for (int goal : goals) {
                if (potential[goal] == LpnNavigationFunction.UNREACHED) {
                    potential[goal] = 0;
                    Worker owner = workers[(goal >>> bandLog2) & 1];
                    owner.queue(goal, 0, 0, LpnNavigationFunction.UNREACHED);
                }
            }
            for (Worker worker : workers) {
                worker.flushNear();
                worker.progress.lastQueued = worker.lastQueued;
                worker.initialSnapshots();
            }
            startHelper();
            Throwable failure = null;
            try {
                workers[0].run();
            } catch (RuntimeException | Error e) {
                failure = e;
                workers[0].abandon();
            }
            awaitHelper();
            Throwable helperProblem = helperFailure;
            if (failure == null && helperProblem != null) {
                failure = helperProblem;
            }
            if (failure instanceof RuntimeException e) {
                throw e;
            }
            if (failure instanceof Error e) {
                throw e;
            }
            return workers[0].finalized + workers[1].finalized;
        }

        private void startHelper() {
            helperFailure = null;
            helperFinished = false;
            if (helper == null) {
                helper = new Thread(this::helperLoop, "sabot-lpn-band-worker");
                helper.setDaemon(true);
                helper.start();
            }
            generation++;
            LockSupport.unpark(helper);
        }

        private void awaitHelper() {
            int spins = 0;
            while (!helperFinished) {
                spins = Worker.pause(spins);
            }
        }

        private void helperLoop() {
            int seen = 0;
            while (true) {
                while (generation == seen && !closed) {
                    LockSupport.park(this);
                }
                if (closed) {
                    return;
                }
                seen = generation;
                try {
                    workers[1].run();
                } catch (RuntimeException | Error e) {
                    helperFailure = e;
                    workers[1].abandon();
                } finally {
                    helperFinished = true;
                }
            }
        }

        void close() {
            closed = true;
            Thread thread = helper;
            if (thread != null) {
                LockSupport.unpark(thread);
                boolean interrupted = false;
                while (thread.isAlive()) {
                    try {
                        thread.join();
                    } catch (InterruptedException e) {
                        interrupted = true;
                    }
                }
                if (interrupted) {
                    Thread.currentThread().interrupt();
                }
            }
        }
    }

    /** Padding on both sides of {@link Progress}' fields, which the other worker polls while this one works. */
    private static class ProgressPadding {
        long p1, p2, p3, p4, p5, p6, p7, p8;
    }

    private static class ProgressFields extends ProgressPadding {
        /** The last bucket finished; {@link Integer#MAX_VALUE} once the worker has stopped. */
        volatile int finished;
        /** The last bucket this worker queued into (own ring or the other's halo) when {@link #finished} was set. */
        volatile int lastQueued;
    }

    private static final class Progress extends ProgressFields {
        long q1, q2, q3, q4, q5, q6, q7, q8;
    }

    /** A growable list of ints. */
    private static final class IntList {
        int[] items = new int[256];
        int size;

        void add(int value) {
            if (size == items.length) {
                items = Arrays.copyOf(items, size * 2);
            }
            items[size++] = value;
        }

        void clear() {
            size = 0;
        }
    }

    private static final class Worker {
        /** Snapshots kept per worker: the other reads that of bucket k - 1 while this one writes that of k. */
        private static final int SNAPSHOTS = 2;
        private static final int INITIAL_CAPACITY = 1024;
        private static final int INITIAL_HALO_CAPACITY = 256;

        final Crew crew;
        final int id;
        /*
         * The other worker's queues and progress, referred to from this object: reading them through the other's
         * object would share a cache line with the counters it updates all the time.
         */
        private int[][] theirHalo;
        private int[] theirHaloSizes;
        private int[][] theirSnapshots;
        private Progress theirProgress;
        final int[][] own;
        final int[] ownSizes;
        /** Cells of the other band with the value bits they were queued with, in pairs; written by the other worker. */
        final int[][] halo;
        final int[] haloSizes;
        final Progress progress = new Progress();
        int[] sortBuffer = new int[0];
        int[] bandCounts = new int[2];
        /**
         * Values of this worker's cells within two rows of a band boundary (the only ones the other worker reads), as
         * they were at the end of a bucket: [{@link #snapshotOf}(k)] after bucket k. The other worker, in bucket k,
         * reads that of bucket k - 1 once this one has finished it; it does not change while the other may read it
         * (this worker cannot finish bucket k + 1 before the other has finished k), so what the other reads does not
         * depend on timing.
         */
        final int[][] snapshots = { new int[0], new int[0] };
        /** Such cells lowered during bucket k, [{@link #snapshotOf}(k)]: copied into the snapshots of k and k + 1. */
        final IntList[] lowered = { new IntList(), new IntList() };
        /** The other worker's snapshot this one reads its cells from (see {@link #snapshots}). */
        int[] theirView;
        int current;
        int lastQueued;
        int finalized;
        /** Cells of the current bucket next to the other band, expanded once the other has finished the one before. */
        int[] deferred = new int[1024];
        /** Cells within two rows of a boundary queued in the current bucket: (cell, bits, bucket) triples. */
        int[] near = new int[3 * 1024];
        int nearSize;
        /** Per run: the ownership band size minus one, and two rows (see {@link #inSnapshotZone}). */
        int bandMask;
        int zoneReach;

        Worker(Crew crew, int id) {
            this.crew = crew;
            this.id = id;
            int ring = crew.bucketMask + 1;
            // the sizes this worker updates all the time and those the other one updates apart in memory
            ownSizes = new int[ring];
            own = new int[ring][];
            halo = new int[ring][];
            for (int i = 0; i < ring; i++) {
                own[i] = new int[INITIAL_CAPACITY];
                halo[i] = new int[INITIAL_HALO_CAPACITY];
            }
            haloSizes = new int[ring];
        }

        void meet(Worker other) {
            theirHalo = other.halo;
            theirHaloSizes = other.haloSizes;
            theirSnapshots = other.snapshots;
            theirProgress = other.progress;
        }

        void reset(int sortBands) {
            for (int i = 0; i < SNAPSHOTS; i++) {
                if (snapshots[i].length != crew.potential.length) {
                    snapshots[i] = new int[crew.potential.length];
                }
                lowered[i].clear();
            }
            Arrays.fill(ownSizes, 0);
            Arrays.fill(haloSizes, 0);
            if (bandCounts.length != sortBands + 2) {
                bandCounts = new int[sortBands + 2];
            }
            bandMask = (1 << crew.bandLog2) - 1;
            zoneReach = 2 * crew.stride;
            nearSize = 0;
            current = -1; // goals are queued before the run: into bucket 0 on both sides
            lastQueued = -1;
            finalized = 0;
            progress.finished = -1;
            progress.lastQueued = -1;
        }

        /** Lets the other worker run to its end after this one failed. */
        void abandon() {
            progress.lastQueued = -1;
            progress.finished = Integer.MAX_VALUE;
        }

        static int pause(int spins) {
            if (spins < 1 << 12) {
                Thread.onSpinWait();
            } else {
                Thread.yield();
            }
            return spins + 1;
        }

        void run() {
            final int[] potential = crew.potential;
            final byte[] costs = crew.costs;
            final float[] halfDensity = crew.halfDensity;
            final int stride = crew.stride;
            final int mask = crew.bucketMask;
            final int sortThreshold = bandCounts.length >> 3;
            try {
                for (int k = 0;; k++) {
                    current = k;
                    int slot = k & mask;
                    if (ownSizes[slot] >= sortThreshold) {
                        sortByMemoryBand(slot);
                    }
                    // first the cells whose four neighbours are this worker's, while the other may still be finishing
                    // bucket k - 1: they read nothing of the other's (see the class comment)
                    int deferredSize = 0;
                    for (int head = 0; head < ownSizes[slot]; head++) {
                        int cell = own[slot][head];
                        int bits = potential[cell];
                        if (bits < 0) {
                            continue; // expanded from an earlier, lower entry
                        }
                        if (nearBoundary(cell)) {
                            if (deferredSize == deferred.length) {
                                deferred = Arrays.copyOf(deferred, 2 * deferredSize);
                            }
                            deferred[deferredSize++] = cell;
                            continue;
                        }
                        potential[cell] = bits | LpnNavigationFunction.FINAL;
                        finalized++;
                        float value = Float.intBitsToFloat(bits);
                        // expand(cell, value, false) written out, so that the hot loop stays one compiled method (as
                        // in the sequential propagation)
                        float ownHalfDensity = halfDensity[costs[cell] & 0xFF];
                        int eastBits = potential[cell + 1];
                        int westBits = potential[cell - 1];
                        int northBits = potential[cell + stride];
                        int southBits = potential[cell - stride];
                        float northValue = LpnNavigationFunction.decode(northBits);
                        float southValue = LpnNavigationFunction.decode(southBits);
                        float eastValue = LpnNavigationFunction.decode(eastBits);
                        float westValue = LpnNavigationFunction.decode(westBits);
                        float northSouthCorner = northValue < southValue ? northValue : southValue;
                        float eastWestCorner = eastValue < westValue ? eastValue : westValue;
                        if (eastBits >= 0) {
                            relax(cell + 1, eastBits, value, northSouthCorner, ownHalfDensity);
                        }
                        if (westBits >= 0) {
                            relax(cell - 1, westBits, value, northSouthCorner, ownHalfDensity);
                        }
                        if (northBits >= 0) {
                            relax(cell + stride, northBits, value, eastWestCorner, ownHalfDensity);
                        }
                        if (southBits >= 0) {
                            relax(cell - stride, southBits, value, eastWestCorner, ownHalfDensity);
                        }
                    }
                    ownSizes[slot] = 0;
                    int spins = 0;
                    while (theirProgress.finished < k - 1) {
                        spins = pause(spins);
                    }
                    if (lastQueued < k && theirProgress.lastQueued < k) {
                        return;
                    }
                    // then the cells next to the other band, which read its snapshot of bucket k - 1, and the other's
                    // cells handed over for this bucket (complete now: it queues them at the latest in bucket k - 1)
                    theirView = theirSnapshots[snapshotOf(k - 1)];
                    for (int i = 0; i < deferredSize; i++) {
                        expandOwn(deferred[i]);
                    }
                    int[] entries = halo[slot];
                    int haloSize = haloSizes[slot];
                    for (int i = 0; i < haloSize; i += 2) {
                        int cell = entries[i];
                        int bits = theirView[cell];
                        if (bits == entries[i + 1]) {
                            expand(cell, Float.intBitsToFloat(bits), true);
                        }
                    }
                    haloSizes[slot] = 0;
                    // an update through a much lower corner (its straight diagonal) may have fallen into this bucket
                    for (int head = 0; head < ownSizes[slot]; head++) {
                        expandOwn(own[slot][head]);
                    }
                    ownSizes[slot] = 0;
                    flushNear();
                    takeSnapshot(k);
                    progress.lastQueued = lastQueued;
                    progress.finished = k;
                }
            } finally {
                progress.finished = Integer.MAX_VALUE;
            }
        }

        /** The snapshot the other worker starts with: its cells near boundaries as they are before the run. */
        void initialSnapshots() {
            int[] potential = crew.potential;
            int zone = 2 * crew.stride + 1;
            int band = 1 << crew.bandLog2;
            for (int boundary = band; boundary - zone < potential.length; boundary += band) {
                int from = Math.max(0, boundary - zone);
                int to = Math.min(potential.length, boundary + zone);
                for (int cell = from; cell < to; cell++) {
                    for (int[] snapshot : snapshots) {
                        snapshot[cell] = potential[cell] & LpnNavigationFunction.VALUE;
                    }
                }
            }
        }

        /**
         * Brings snapshot {@code snapshotOf(k)} up to date at the end of bucket k: it lacks what was lowered in buckets
         * k - 1 and k.
         */
        private void takeSnapshot(int k) {
            int[] snapshot = snapshots[snapshotOf(k)];
            int[] potential = crew.potential;
            for (int b = k - SNAPSHOTS + 1; b <= k; b++) {
                IntList list = lowered[snapshotOf(b)];
                int[] cells = list.items;
                for (int i = 0; i < list.size; i++) {
                    snapshot[cells[i]] = potential[cells[i]] & LpnNavigationFunction.VALUE;
                }
            }
            lowered[snapshotOf(k + 1)].clear(); // bucket k - 1's, now in both snapshots: the list of bucket k + 1
        }

        /** @return the snapshot taken at the end of bucket k, and the list of the cells lowered in it */
        static int snapshotOf(int k) {
            return Math.floorMod(k, SNAPSHOTS);
        }

        /**
         * @return whether the other worker may read this cell: within two rows of a band boundary (or of the grid's
         *         start), {@code cell + 2 stride} lying less than four rows into a band
         */
        private boolean inSnapshotZone(int cell) {
            return ((cell + zoneReach) & bandMask) < 2 * zoneReach;
        }

        /** @return whether the row above or below the cell lies in the other band (or before the grid's start) */
        private boolean nearBoundary(int cell) {
            return ((cell + crew.stride) & bandMask) < 2 * crew.stride;
        }

        private boolean owns(int cell) {
            return ((cell >>> crew.bandLog2) & 1) == id;
        }

        /**
         * Updates the axis neighbours of a final cell (own or, from the halo, the other's) that this worker owns; see
         * {@link LpnNavigationFunction} for why the four neighbours are read once.
         */
        private void expand(int cell, float value, boolean checkOwner) {
            final int stride = crew.stride;
            float ownHalfDensity = crew.halfDensity[crew.costs[cell] & 0xFF];
            int eastBits = read(cell + 1, checkOwner);
            int westBits = read(cell - 1, checkOwner);
            int northBits = read(cell + stride, checkOwner);
            int southBits = read(cell - stride, checkOwner);
            float northSouthCorner = Math.min(LpnNavigationFunction.decode(northBits),
                    LpnNavigationFunction.decode(southBits));
            float eastWestCorner = Math.min(LpnNavigationFunction.decode(eastBits),
                    LpnNavigationFunction.decode(westBits));
            if (eastBits >= 0 && (!checkOwner || owns(cell + 1))) {
                relax(cell + 1, eastBits, value, northSouthCorner, ownHalfDensity);
            }
            if (westBits >= 0 && (!checkOwner || owns(cell - 1))) {
                relax(cell - 1, westBits, value, northSouthCorner, ownHalfDensity);
            }
            if (northBits >= 0 && (!checkOwner || owns(cell + stride))) {
                relax(cell + stride, northBits, value, eastWestCorner, ownHalfDensity);
            }
            if (southBits >= 0 && (!checkOwner || owns(cell - stride))) {
                relax(cell - stride, southBits, value, eastWestCorner, ownHalfDensity);
            }
        }

        /**
         * A neighbour's bits: this worker's from the grid, the other's from the snapshot the other finished before
         * this bucket (without final flag: never a target here, a corner only).
         */
        private int read(int cell, boolean maybeOthers) {
            if (!maybeOthers || owns(cell)) {
                return crew.potential[cell];
            }
            return theirView[cell];
        }

        private void relax(int target, int targetBits, float value, float corner, float ownHalfDensity) {
            float c = crew.halfDensity[crew.costs[target] & 0xFF] + ownHalfDensity;
            float best = LpnNavigationFunction.update(value, corner, c);
            int bestBits = Float.floatToRawIntBits(best);
            if (bestBits < targetBits) {
                crew.potential[target] = bestBits;
                queue(target, bestBits, (int) (best * crew.inverseBucketWidth), targetBits);
            }
        }

        /** Queues a cell just lowered from {@code oldBits} to {@code bits} (bucket {@code bucket} by its value). */
        void queue(int cell, int bits, int bucket, int oldBits) {
            int ownBucket = Math.max(bucket, current);
            // still queued in the same bucket: that entry reads the lower value when it comes up
            if (oldBits == LpnNavigationFunction.UNREACHED
                    || (int) (Float.intBitsToFloat(oldBits) * crew.inverseBucketWidth) != bucket) {
                int slot = ownBucket & crew.bucketMask;
                int size = ownSizes[slot];
                int[] items = own[slot];
                if (size == items.length) {
                    items = Arrays.copyOf(items, size * 2);
                    own[slot] = items;
                }
                items[size] = cell;
                ownSizes[slot] = size + 1;
                lastQueued = Math.max(lastQueued, ownBucket);
            }
            if (inSnapshotZone(cell)) {
                // the rest at the end of the bucket (nearBoundaryQueued): a call here, even one rarely made, slows the
                // whole propagation loop by a third (measured: 30 against 22 ms for 1M cells on one worker)
                int size = nearSize;
                if (size + 3 > near.length) {
                    near = Arrays.copyOf(near, 2 * near.length);
                }
                near[size] = cell;
                near[size + 1] = bits;
                near[size + 2] = bucket;
                nearSize = size + 3;
            }
        }

        /** Completes {@link #queue} for the cells within two rows of a boundary queued since the last call. */
        void flushNear() {
            for (int i = 0; i < nearSize; i += 3) {
                nearBoundaryQueued(near[i], near[i + 1], near[i + 2]);
            }
            nearSize = 0;
        }

        /** Expands a cell of this worker unless it is final already (expanded from an earlier, lower entry). */
        private void expandOwn(int cell) {
            int bits = crew.potential[cell];
            if (bits >= 0) {
                crew.potential[cell] = bits | LpnNavigationFunction.FINAL;
                finalized++;
                expand(cell, Float.intBitsToFloat(bits), nearBoundary(cell));
            }
        }

        /**
         * Notes a cell within two rows of a boundary for the next snapshot and, if it has neighbours in the other band,
         * hands it to the other worker's halo.
         */
        private void nearBoundaryQueued(int cell, int bits, int bucket) {
            lowered[snapshotOf(current)].add(cell);
            if (nearBoundary(cell)) {
                // the other worker expands it for its own neighbours, at the earliest in its next bucket
                int haloBucket = Math.max(bucket, current + 1);
                int slot = haloBucket & crew.bucketMask;
                int size = theirHaloSizes[slot];
                int[] entries = theirHalo[slot];
                if (size + 2 > entries.length) {
                    entries = Arrays.copyOf(entries, entries.length * 2);
                    theirHalo[slot] = entries;
                }
                entries[size] = cell;
                entries[size + 1] = bits;
                theirHaloSizes[slot] = size + 2;
                lastQueued = Math.max(lastQueued, haloBucket);
            }
        }

        private void sortByMemoryBand(int slot) {
            int[] items = own[slot];
            if (sortBuffer.length < items.length) {
                sortBuffer = new int[items.length];
            }
            own[slot] = LpnNavigationFunction.sortByMemoryBand(items, ownSizes[slot], sortBuffer, bandCounts,
                    crew.sortBandLog2);
            sortBuffer = items;
        }
    }
}

package sabot.planner.internal;

import java.util.Arrays;

/**
 * A binary min-heap of cells (padded indices) keyed by a float: the queue of a repair's checks and seeds
 * ({@link NavigationRepair}). Two flat arrays, no boxing; cells of equal key leave in an order fixed by the sequence
 * of operations, so that results are repeatable. (The reference search keeps the same heap in its own fields: its
 * loop pushes and pops for every cell, and there the fields of another object cost a load more per operation.)
 */
final class CellHeap {

    private float[] keys;
    private int[] cells;
    private int size;

    /** @param capacity cells held before the arrays grow */
    CellHeap(int capacity) {
        keys = new float[capacity];
        cells = new int[capacity];
    }

    boolean isEmpty() {
        return size == 0;
    }

    void clear() {
        size = 0;
    }

    /** @return the lowest key (only when not {@link #isEmpty}) */
    float lowestKey() {
        return keys[0];
    }

    /** @return the cell of the lowest key (only when not {@link #isEmpty}) */
    int lowestCell() {
        return cells[0];
    }

    void push(int cell, float key) {
        if (size == keys.length) {
            keys = Arrays.copyOf(keys, size * 2);
            cells = Arrays.copyOf(cells, size * 2);
        }
        int i = size++;
        while (i > 0) {
            int parent = (i - 1) >>> 1;
            if (keys[parent] <= key) {
                break;
            }
            keys[i] = keys[parent];
            cells[i] = cells[parent];
            i = parent;
        }
        keys[i] = key;
        cells[i] = cell;
    }

    /** @return the cell of the lowest key, removed (only when not {@link #isEmpty}) */
    int pop() {
        int top = cells[0];
        removeLowest();
        return top;
    }

    /** Removes the cell of the lowest key (only when not {@link #isEmpty}). */
    void removeLowest() {
        int last = --size;
        if (last == 0) {
            return;
        }
        float key = keys[last];
        int cell = cells[last];
        int i = 0;
        while (true) {
            int child = 2 * i + 1;
            if (child >= last) {
                break;
            }
            if (child + 1 < last && keys[child + 1] < keys[child]) {
                child++;
            }
            if (keys[child] >= key) {
                break;
            }
            keys[i] = keys[child];
            cells[i] = cells[child];
            i = child;
        }
        keys[i] = key;
        cells[i] = cell;
    }
}

package sabot.planner.internal;

import java.util.Arrays;

import sabot.planner.CostModel;

/**
 * The optimality reference: a plain 8-connected shortest-path search over a {@link PlanningGrid} with the
 * {@link CostModel}'s step cost {@code |p - q| * (h(p) + h(q)) / 2}, diagonal steps only when both side cells are
 * passable (the same rule as LPN, so both reach exactly the same cells). Searches from the goal set towards the start
 * with a binary heap; with the octile distance times the least density as heuristic it is A* (P. Hart, N. Nilsson,
 * B. Raphael, IEEE SSC 4(2), 1968), which is admissible and consistent here, so the first time the start is taken
 * from the heap its cost is the grid optimum; without the heuristic it is Dijkstra's algorithm.
 */
public final class ReferenceSearch {

    private static final float SQRT2 = (float) Math.sqrt(2);
    private static final int UNREACHED = LpnNavigationFunction.UNREACHED;
    // opposite directions differ in the lowest bit: k ^ 1
    private static final int[] DX = { 1, -1, 0, 0, 1, -1, 1, -1 };
    private static final int[] DY = { 0, 0, 1, -1, 1, -1, -1, 1 };

    private final float[] density;
    private final float minDensity;
    private final boolean useHeuristic;

    private PlanningGrid grid;
    /** Cost to goal as float bits (non-negative floats order like their bits); +infinity where not reached. */
    private int[] cost = new int[0];
    private byte[] closed = new byte[0];
    private byte[] towardsGoal = new byte[0];
    private int[] touched = new int[0];
    private int touchedCount;
    private int closedCount;
    private float[] heapKeys = new float[1024];
    private int[] heapCells = new int[1024];
    private int heapSize;

    /** @param useHeuristic true for A*, false for Dijkstra */
    public ReferenceSearch(CostModel costModel, boolean useHeuristic) {
        this.density = costModel.densityTable();
        this.minDensity = costModel.minDensity();
        this.useHeuristic = useHeuristic;
    }

    /**
     * @return cost to goal by padded index as value bits ({@link LpnNavigationFunction#decode}; {@code +infinity}
     *         where not reached); valid until the next search
     */
    public int[] costBits() {
        return cost;
    }

    /** @return cells settled by the last search */
    public int closedCount() {
        return closedCount;
    }

    /**
     * @param goals padded indices of passable goal cells
     * @param start padded index of a passable start cell
     * @return true when the start was reached
     */
    public boolean search(PlanningGrid planningGrid, int[] goals, int start) {
        prepare(planningGrid);
        int stride = grid.stride();
        int startColumn = start % stride;
        int startRow = start / stride;
        byte[] costs = grid.costs();
        for (int goal : goals) {
            if (cost[goal] != 0) {
                touch(goal);
                cost[goal] = 0;
                towardsGoal[goal] = -1;
                heapPush(heuristic(goal, stride, startColumn, startRow), goal);
            }
        }
        while (heapSize > 0) {
            int cell = heapCells[0];
            heapPop();
            if (closed[cell] != 0) {
                continue;
            }
            closed[cell] = 1;
            closedCount++;
            if (cell == start) {
                return true;
            }
            float cellDensity = density[costs[cell] & 0xFF];
            for (int k = 0; k < 8; k++) {
                int next = cell + DX[k] + DY[k] * stride;
                if (closed[next] != 0) {
                    continue;
                }
                float nextDensity = density[costs[next] & 0xFF];
                if (nextDensity == Float.POSITIVE_INFINITY) {
                    continue;
                }
                float step = 0.5f * (cellDensity + nextDensity);
                if (k >= 4) {
                    if (density[costs[cell + DX[k]] & 0xFF] == Float.POSITIVE_INFINITY
                            || density[costs[cell + DY[k] * stride] & 0xFF] == Float.POSITIVE_INFINITY) {
                        continue;
                    }
                    step *= SQRT2;
                }
                float candidate = Float.intBitsToFloat(cost[cell]) + step;
                int candidateBits = Float.floatToRawIntBits(candidate);
                if (candidateBits < cost[next]) {
                    if (cost[next] == UNREACHED) {
                        touch(next);
                    }
                    cost[next] = candidateBits;
                    towardsGoal[next] = (byte) (k ^ 1);
                    heapPush(candidate + heuristic(next, stride, startColumn, startRow), next);
                }
            }
        }
        return false;
    }

    /** @return padded indices from {@code start} to a goal cell, following the search tree */
    public int[] cellPath(int start) {
        int stride = grid.stride();
        int length = 1;
        for (int cell = start; towardsGoal[cell] >= 0; cell += DX[towardsGoal[cell]] + DY[towardsGoal[cell]] * stride) {
            length++;
        }
        int[] path = new int[length];
        int cell = start;
        for (int i = 0; i < length; i++) {
            path[i] = cell;
            if (towardsGoal[cell] >= 0) {
                cell += DX[towardsGoal[cell]] + DY[towardsGoal[cell]] * stride;
            }
        }
        return path;
    }

    private float heuristic(int cell, int stride, int startColumn, int startRow) {
        if (!useHeuristic) {
            return 0f;
        }
        int dx = Math.abs(cell % stride - startColumn);
        int dy = Math.abs(cell / stride - startRow);
        return minDensity * (Math.max(dx, dy) + (SQRT2 - 1) * Math.min(dx, dy));
    }

    private void prepare(PlanningGrid planningGrid) {
        int size = planningGrid.paddedSize();
        if (cost.length != size) {
            cost = new int[size];
            Arrays.fill(cost, UNREACHED);
            closed = new byte[size];
            towardsGoal = new byte[size];
            touched = new int[size];
        } else {
            for (int i = 0; i < touchedCount; i++) {
                cost[touched[i]] = UNREACHED;
                closed[touched[i]] = 0;
            }
        }
        grid = planningGrid;
        touchedCount = 0;
        closedCount = 0;
        heapSize = 0;
    }

    private void touch(int cell) {
        touched[touchedCount++] = cell;
    }

    private void heapPush(float key, int cell) {
        if (heapSize == heapKeys.length) {
            heapKeys = Arrays.copyOf(heapKeys, heapSize * 2);
            heapCells = Arrays.copyOf(heapCells, heapSize * 2);
        }
        int i = heapSize++;
        while (i > 0) {
            int parent = (i - 1) >>> 1;
            if (heapKeys[parent] <= key) {
                break;
            }
            heapKeys[i] = heapKeys[parent];
            heapCells[i] = heapCells[parent];
            i = parent;
        }
        heapKeys[i] = key;
        heapCells[i] = cell;
    }

    private void heapPop() {
        int last = --heapSize;
        if (last == 0) {
            return;
        }
        float key = heapKeys[last];
        int cell = heapCells[last];
        int i = 0;
        while (true) {
            int child = 2 * i + 1;
            if (child >= last) {
                break;
            }
            if (child + 1 < last && heapKeys[child + 1] < heapKeys[child]) {
                child++;
            }
            if (heapKeys[child] >= key) {
                break;
            }
            heapKeys[i] = heapKeys[child];
            heapCells[i] = heapCells[child];
            i = child;
        }
        heapKeys[i] = key;
        heapCells[i] = cell;
    }
}

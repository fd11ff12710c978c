/* The machine's ceiling for the harness's 2-rank rows (scripts/bench/bench.py): an ideal
 * bulk-synchronous code with gendpde's synchronisation pattern and no extra work on more
 * ranks. A step is WORK multiply-adds split evenly over the ranks, in ROUNDS chunks; after
 * each chunk a rank sends BYTES/ROUNDS bytes to each neighbour along a ring and receives as
 * much from both (one round: the messages overlap, as gendpde's exchanges of a round), and
 * the step ends with COLLS one-value reductions. Its arithmetic touches no memory, so its
 * parallel efficiency is what the cores' availability and the exchanges' latency allow.
 *
 *   sync_kernel WORK ROUNDS BYTES COLLS STEPS  ->  "steps/s <rate>"
 */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

/* Four independent chains of dependent multiply-adds, n iterations. */
static double chunk(long n, double x) {
    double a = x, b = x + 1e-3, c = x + 2e-3, d = x + 3e-3;
    for (long i = 0; i < n; i++) {
        a = a * 0.999999 + 1e-7;
        b = b * 0.999998 + 2e-7;
        c = c * 0.999997 + 3e-7;
        d = d * 0.999996 + 4e-7;
    }
    return 0.25 * (a + b + c + d);
}

int main(int argc, char **argv) {
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (argc != 6) {
        if (rank == 0) fprintf(stderr, "usage: sync_kernel WORK ROUNDS BYTES COLLS STEPS\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    long work = atol(argv[1]), bytes = atol(argv[3]);
    int rounds = atoi(argv[2]), colls = atoi(argv[4]), steps = atoi(argv[5]);
    if (work <= 0 || rounds <= 0 || bytes < 0 || colls < 0 || steps <= 0) {
        if (rank == 0) fprintf(stderr, "sync_kernel: WORK, ROUNDS and STEPS must be positive, BYTES and COLLS not negative\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    long per = work / size / rounds;
    int len = size > 1 ? (int)(bytes / rounds) : 0;
    char *buf = calloc(4 * (size_t)len + 1, 1);
    int left = (rank + size - 1) % size, right = (rank + 1) % size;
    double x = 0.5, t0 = 0.0;
    for (int s = -1; s < steps; s++) { /* step -1 warms up, untimed */
        if (s == 0) {
            MPI_Barrier(MPI_COMM_WORLD);
            t0 = MPI_Wtime();
        }
        for (int r = 0; r < rounds; r++) {
            x = chunk(per, x);
            if (size > 1) {
                MPI_Request req[4];
                MPI_Irecv(buf + 2 * len, len, MPI_CHAR, left, 0, MPI_COMM_WORLD, &req[0]);
                MPI_Irecv(buf + 3 * len, len, MPI_CHAR, right, 1, MPI_COMM_WORLD, &req[1]);
                MPI_Isend(buf, len, MPI_CHAR, right, 0, MPI_COMM_WORLD, &req[2]);
                MPI_Isend(buf + len, len, MPI_CHAR, left, 1, MPI_COMM_WORLD, &req[3]);
                MPI_Waitall(4, req, MPI_STATUSES_IGNORE);
            }
        }
        for (int c = 0; c < colls; c++) {
            double y = x;
            MPI_Allreduce(&y, &x, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        }
    }
    double t = MPI_Wtime() - t0, tmax;
    MPI_Reduce(&t, &tmax, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    /* x keeps the arithmetic from being optimised away */
    if (rank == 0) printf("steps/s %.6g (checksum %.6f)\n", steps / tmax, x);
    free(buf);
    MPI_Finalize();
    return 0;
}

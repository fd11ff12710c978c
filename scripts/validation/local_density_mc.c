/* Metropolis Monte Carlo of eq 92's configurational weight exp(-sum_i f(n_i)), the
 * compiled kernel of local_density_mc.py (which writes the table of f, compiles and runs
 * this file and reads its output; the Python loop took 20 minutes for 100 sweeps of 1331
 * particles).
 *
 *   local_density_mc CELLS RHO RC T SWEEPS EQUIL SEED TABLE OUT
 *
 * TABLE: doubles n0, dn, M, then M values of f (units of k_B T) and M of df/dn on the grid
 * n0 + k dn (linear interpolation, clamped at the ends). Particles start on an sc lattice of
 * CELLS^3 sites at density RHO; quadratic weight w(r) = 15/(2 pi rc^3) (1 - r/rc)^2, self
 * term excluded; single-particle moves, the step raised towards 40 % acceptance every 5
 * sweeps of equilibration (it may exceed the box: random re-insertion, still symmetric);
 * all n_i recomputed every sweep. OUT (doubles): per sampled sweep P, <n_i>, var(n_i), then
 * the 200-bin histogram of n_i on [0, 1), then 64 n_i per sampled sweep, then the final step
 * and acceptance. P = rho k_B T + <sum_{i<j} r_ij . f_ij>/(3V) with the pair force
 * -(F'(n_i) + F'(n_j)) w'(r) e_ij, F = k_B T f (eq 50 with pi/n^2 = F').
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static uint64_t rng_state;

static uint64_t next_u64(void) { /* splitmix64 */
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static double uniform(void) { return (next_u64() >> 11) * 0x1.0p-53; }

static double n0, dn, *ftab, *dftab;
static long m;

static double interp(const double *tab, double n) {
    double x = (n - n0) / dn;
    if (x <= 0.0) return tab[0];
    if (x >= (double)(m - 1)) return tab[m - 1];
    long k = (long)x;
    double a = x - (double)k;
    return tab[k] * (1.0 - a) + tab[k + 1] * a;
}

static double rc, norm, box;

/* Minimum-image distance, or rc for pairs at or beyond rc (both points inside the box). */
static double dist(const double *a, const double *b) {
    double s = 0.0;
    for (int d = 0; d < 3; d++) {
        double x = fabs(a[d] - b[d]);
        x = x > 0.5 * box ? box - x : x;
        s += x * x;
    }
    return s < rc * rc ? sqrt(s) : rc;
}

static double weight(double r) {
    double q = 1.0 - r / rc;
    return norm * q * q;
}

int main(int argc, char **argv) {
    if (argc != 10) {
        fprintf(stderr, "usage: %s CELLS RHO RC T SWEEPS EQUIL SEED TABLE OUT\n", argv[0]);
        return 2;
    }
    int cells = atoi(argv[1]);
    double rho = atof(argv[2]), T = atof(argv[4]);
    rc = atof(argv[3]);
    long sweeps = atol(argv[5]), equil = atol(argv[6]);
    rng_state = strtoull(argv[7], NULL, 10);
    FILE *tf = fopen(argv[8], "rb");
    double head[3];
    if (!tf || fread(head, sizeof(double), 3, tf) != 3) return 3;
    n0 = head[0], dn = head[1], m = (long)head[2];
    ftab = malloc(m * sizeof(double)), dftab = malloc(m * sizeof(double));
    if (fread(ftab, sizeof(double), m, tf) != (size_t)m || fread(dftab, sizeof(double), m, tf) != (size_t)m) return 3;
    fclose(tf);

    long N = (long)cells * cells * cells;
    box = cells / cbrt(rho);
    norm = 15.0 / (2.0 * M_PI * rc * rc * rc);
    double *pos = malloc(3 * N * sizeof(double)), *n = calloc(N, sizeof(double));
    double *w_old = malloc(N * sizeof(double)), *w_new = malloc(N * sizeof(double));
    double *rec = malloc(3 * sweeps * sizeof(double)), *samples = malloc(64 * sweeps * sizeof(double));
    double hist[200] = {0};
    for (long i = 0; i < N; i++) {
        pos[3 * i] = (i / (cells * cells) + 0.5) * box / cells;
        pos[3 * i + 1] = ((i / cells) % cells + 0.5) * box / cells;
        pos[3 * i + 2] = (i % cells + 0.5) * box / cells;
    }
    double step = 1.0;
    long accepted = 0, tried = 0;
    for (long sweep = 0; sweep < equil + sweeps; sweep++) {
        for (long i = 0; i < N; i++) n[i] = 0.0;
        double vir = 0.0;
        for (long i = 0; i < N; i++)
            for (long j = i + 1; j < N; j++) {
                double w = weight(dist(pos + 3 * i, pos + 3 * j));
                n[i] += w, n[j] += w;
            }
        if (sweep >= equil) {
            long s = sweep - equil;
            double mean = 0.0, sq = 0.0;
            for (long i = 0; i < N; i++) {
                mean += n[i], sq += n[i] * n[i];
                int b = (int)(n[i] * 200.0);
                if (b >= 0 && b < 200) hist[b] += 1.0;
            }
            mean /= N;
            for (long i = 0; i < N; i++) w_old[i] = interp(dftab, n[i]); /* F'(n_i)/T */
            for (long i = 0; i < N; i++)
                for (long j = i + 1; j < N; j++) {
                    double r = dist(pos + 3 * i, pos + 3 * j);
                    if (r < rc) vir += (w_old[i] + w_old[j]) * 2.0 * norm * (1.0 - r / rc) / rc * r;
                }
            rec[3 * s] = rho * T + T * vir / (3.0 * box * box * box);
            rec[3 * s + 1] = mean;
            rec[3 * s + 2] = sq / N - mean * mean;
            for (int k = 0; k < 64; k++) samples[64 * s + k] = n[next_u64() % N];
        }
        for (long mv = 0; mv < N; mv++) {
            long k = next_u64() % N;
            double cand[3];
            for (int d = 0; d < 3; d++) cand[d] = fmod(fmod(pos[3 * k + d] + step * (2.0 * uniform() - 1.0), box) + box, box);
            double nk = 0.0, df = 0.0;
            for (long j = 0; j < N; j++) {
                if (j == k) {
                    w_old[j] = w_new[j] = 0.0;
                    continue;
                }
                w_old[j] = weight(dist(pos + 3 * k, pos + 3 * j));
                w_new[j] = weight(dist(cand, pos + 3 * j));
                nk += w_new[j];
                if (w_old[j] > 0.0 || w_new[j] > 0.0)
                    df += interp(ftab, n[j] - w_old[j] + w_new[j]) - interp(ftab, n[j]);
            }
            df += interp(ftab, nk) - interp(ftab, n[k]);
            tried++;
            if (df <= 0.0 || uniform() < exp(-df)) {
                accepted++;
                for (long j = 0; j < N; j++) n[j] += w_new[j] - w_old[j];
                n[k] = nk;
                for (int d = 0; d < 3; d++) pos[3 * k + d] = cand[d];
            }
        }
        if (sweep < equil && sweep % 5 == 4) {
            step *= exp((double)accepted / tried - 0.4);
            accepted = tried = 0;
        }
    }
    FILE *out = fopen(argv[9], "wb");
    if (!out) return 4;
    double tail[2] = {step, (double)accepted / (tried ? tried : 1)};
    fwrite(rec, sizeof(double), 3 * sweeps, out);
    fwrite(hist, sizeof(double), 200, out);
    fwrite(samples, sizeof(double), 64 * sweeps, out);
    fwrite(tail, sizeof(double), 2, out);
    fclose(out);
    return 0;
}

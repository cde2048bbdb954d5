/* Plain textbook FASTSIM (Kalker 1982): the brush march with radial return onto the
 * Coulomb bound mu p, on the same discretisation as the project's steady FASTSIM:
 * ny strips at the Gauss-Legendre nodes eta_j with their weights as widths, nx cells per
 * strip, nodes xi_k = l_j - k dxi, the bound taken at the end node (no closer to the
 * trailing edge than TRAILING_NODE cells), the spin lever arm at the move's midpoint,
 * trapezoidal quadrature. Reference for the benchmark only: gcc -O2, nothing clever.
 * Returns F_x (N), writes F_y. */
#include <math.h>

/* 4 zeta(-1/2)^2, creep-core engine/grid.rs TRAILING_NODE */
#define TRAILING_NODE 0.172866730280115

/* The j-th of ny Gauss-Legendre nodes on (-1, 1), ascending; its weight in *w. */
static double gauss_node(int j, int ny, double *w)
{
    const double pi = 3.14159265358979323846;
    double x = -cos(pi * (j + 0.75) / (ny + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; it++) {
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= ny; k++) {
            double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        dp = ny * (x * p1 - p0) / (x * x - 1.0);
        double dx = p1 / dp;
        x -= dx;
        if (fabs(dx) < 1e-15)
            break;
    }
    *w = 2.0 / ((1.0 - x * x) * dp * dp);
    return x;
}

double fastsim_ref(int nx, int ny, double a, double b, double p0, double mu,
                   double lx, double ly, double ls, double cx, double cy, double cs,
                   double *fy_out)
{
    double fx = 0.0, fy = 0.0;
    for (int j = 0; j < ny; j++) {
        double weight;
        double eta = gauss_node(j, ny, &weight);
        double dy = weight * b;
        double l = sqrt(1.0 - eta * eta);
        double dxi = 2.0 * l / nx;
        double d = dxi * a;
        double y = eta * b;
        double tx = 0.0, ty = 0.0;
        double sx = 0.5 * tx, sy = 0.5 * ty; /* node 0: zero stress, half weight */
        for (int k = 1; k <= nx; k++) {
            double xi = l - k * dxi;
            double x = a * (xi + 0.5 * dxi);
            tx += d * (cx / lx - cs * y / ls);
            ty += d * (cy / ly + cs * x / ls);
            double xe = xi > -l + TRAILING_NODE * dxi ? xi : -l + TRAILING_NODE * dxi;
            double r = 1.0 - xe * xe - eta * eta;
            double g = r > 0.0 ? mu * p0 * sqrt(r) : 0.0;
            double n = sqrt(tx * tx + ty * ty);
            if (g <= 0.0) {
                tx = 0.0;
                ty = 0.0;
            } else if (n > g) {
                tx *= g / n;
                ty *= g / n;
            }
            double w = k < nx ? 1.0 : 0.5;
            sx += w * tx;
            sy += w * ty;
        }
        fx += sx * dxi * a * dy;
        fy += sy * dxi * a * dy;
    }
    *fy_out = fy;
    return fx;
}

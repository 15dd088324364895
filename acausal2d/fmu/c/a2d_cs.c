#include "a2d_cs.h"
void a2d_cs_setup(a2d_cs* s, double tol) { s->rtol = tol > 0 ? tol : 1e-8; s->atol = 1e-10; s->h = 0; s->steps = 0; }
int a2d_cs_advance(a2d_cs* s, a2d_core* c, double t_end) { (void)s; (void)c; (void)t_end; return -1; }

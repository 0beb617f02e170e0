"""The contact laws' ops tables (src/contact/laws/) on a single contact point, against values
worked out by hand, and a law registered from outside through the registry. A small C program,
linked against build/libboltrom.a, drives one contact state through the state's own loops
(augmentation, active-set update with the return map, end of a solve, energy terms, point codes)."""
import subprocess

import pytest

from conftest import ENV, ROOT

PROGRAM = r"""
#include "private/contact.h"

static int failures = 0;
#define EXPECT(cond, ...) do { if (!(cond)) { failures++; printf("FAILED %s:%d ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)
#define NEAR(a, b) (PetscAbsReal((a) - (b)) <= 1e-12 * (1 + PetscAbsReal(b)))

/* One contact element whose point 0 is closed (normal +z) and whose other points are open;
   normal penalty 10, tangential 4, stick stiffness 4, friction 0.5, point weights 1. */
static PetscErrorCode Scene(BoltMesh *m, const char law[], BoltContactSet **cp, BoltContactState **sp)
{
  BoltContactSet *c;
  PetscBool       active[4] = {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetCreate(m, &c));
  PetscCall(BoltContactLawCreate(BoltMeshComm(m), law, &c->law));
  c->npairs = 1;
  c->nelem  = 1;
  c->ngpGlobal = 4;
  PetscCall(PetscCalloc1(1, &c->elem));
  PetscCall(PetscCalloc3(16, &c->gpN, 4, &c->gpW, 12, &c->gpNormal));
  PetscCall(PetscCalloc1(1, &c->nodalArea));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 1, &c->layout)); /* the layout a state's work space copies */
  for (PetscInt q = 0; q < 4; q++) {
    c->gpW[q]              = 1;
    c->gpNormal[3 * q + 2] = 1;
  }
  c->epsN[0] = 10;
  c->epsT[0] = 4;
  c->stickStiffness[0] = 4;
  c->friction[0]       = 0.5;
  c->bandTraction[0]   = 1e-10;
  c->activationGap     = 1e-9;
  PetscCall(BoltContactStateCreate(c, sp));
  PetscCall(BoltContactStateSetActive(*sp, active, NULL));
  *cp = c;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetGap(BoltContactState *s, PetscReal x, PetscReal y, PetscReal z)
{
  PetscFunctionBeginUser;
  s->gap[0] = x;
  s->gap[1] = y;
  s->gap[2] = z;
  PetscFunctionReturn(0);
}

/* stick: t = lambda + epsT g + (epsN - epsT) (g.n) n; the violation is the penetration. */
static PetscErrorCode TestStick(BoltMesh *m)
{
  BoltContactSet   *c;
  BoltContactState *s;
  PetscReal         rel, pen;
  unsigned char     codes[4];

  PetscFunctionBeginUser;
  PetscCall(Scene(m, "stick", &c, &s));
  EXPECT(!BoltContactSetIsComplementarity(c) && !BoltContactSetHasFriction(c) && BoltContactStateHasPenaltyEnergy(s), "stick: properties");
  EXPECT(c->law->penaltyFactor == 200, "stick: penalty factor %g", (double)c->law->penaltyFactor);
  PetscCall(SetGap(s, 1, 2, -3));
  PetscCall(BoltContactStateAugment(s, &rel, &pen));
  EXPECT(s->lambda[0] == 4 && s->lambda[1] == 8 && s->lambda[2] == -30, "stick: trial traction (%g %g %g)", (double)s->lambda[0], (double)s->lambda[1], (double)s->lambda[2]);
  EXPECT(pen == 3, "stick: violation %g, not the penetration 3", (double)pen);
  BoltContactStatePointCodes(s, codes);
  EXPECT(codes[0] == BOLT_POINT_STICK && codes[1] == BOLT_POINT_OPEN, "stick: point codes %d %d", codes[0], codes[1]);
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(BoltContactSetDestroy(&c));
  PetscFunctionReturn(0);
}

/* strict: the same traction; a sticking pair's violation is its whole gap |g|; the open points
   of a stored state slide, and a pair that closes again is re-anchored where it closes. */
static PetscErrorCode TestStrict(BoltMesh *m)
{
  BoltContactSet   *c;
  BoltContactState *s;
  PetscReal         rel, pen, tn[4] = {-30, 0, 0, 0};
  PetscInt          nchanged;
  PetscBool         cycling;
  unsigned char     codes[4];

  PetscFunctionBeginUser;
  PetscCall(Scene(m, "strict", &c, &s));
  EXPECT(BoltContactSetIsComplementarity(c) && !BoltContactSetHasFriction(c) && !BoltContactStateHasPenaltyEnergy(s) && BoltContactStateLambdaIsTraction(s), "strict: properties");
  EXPECT(c->law->penaltyFactor == 3e7, "strict: penalty factor %g", (double)c->law->penaltyFactor);
  EXPECT(!s->released[0] && s->released[1], "strict: a stored state's open points slide");
  PetscCall(SetGap(s, 1, 2, -3));
  PetscCall(BoltContactStateAugment(s, &rel, &pen));
  EXPECT(s->lambda[0] == 4 && s->lambda[1] == 8 && s->lambda[2] == -30, "strict: trial traction");
  EXPECT(NEAR(pen, PetscSqrtReal(14.0)), "strict: violation %g, not |g| = sqrt(14)", (double)pen);
  /* point 1 penetrates: it closes again, and sticks where it closes (its tangential gap) */
  s->gap[3] = 0.5;
  s->gap[5] = -1;
  PetscCall(BoltContactStateUpdateActive(s, tn, &nchanged, &cycling));
  EXPECT(nchanged == 1 && s->active[1], "strict: point 1 closes (%d changed)", (int)nchanged);
  EXPECT(s->anchor[3] == 0.5 && s->gap[3] == 0 && s->gap[5] == -1, "strict: re-anchored at (%g, %g), gap (%g, %g)", (double)s->anchor[3], (double)s->anchor[5], (double)s->gap[3], (double)s->gap[5]);
  BoltContactStatePointCodes(s, codes);
  EXPECT(codes[0] == BOLT_POINT_STICK && codes[1] == BOLT_POINT_SLIP && codes[2] == BOLT_POINT_OPEN, "strict: point codes %d %d %d", codes[0], codes[1], codes[2]);
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(BoltContactSetDestroy(&c));
  PetscFunctionReturn(0);
}

/* coulomb: normal part as the strict law's, tangential part the elastic stick k_t g_T while
   inside the cone mu |t_N|, on the cone once beyond it; the work, the dissipation over the slip
   and the stick energy at the end of the solve. */
static PetscErrorCode TestCoulomb(BoltMesh *m)
{
  BoltContactSet   *c;
  BoltContactState *s;
  PetscReal         rel, pen, tn[4] = {-30, 0, 0, 0}, energy;
  PetscInt          nchanged;
  PetscBool         cycling;
  unsigned char     codes[4];

  PetscFunctionBeginUser;
  PetscCall(Scene(m, "coulomb", &c, &s));
  EXPECT(BoltContactSetIsComplementarity(c) && BoltContactSetHasFriction(c) && BoltContactStateHasFriction(s), "coulomb: properties");
  EXPECT(c->law->penaltyFactor == 1e6, "coulomb: penalty factor %g", (double)c->law->penaltyFactor);
  EXPECT(!s->released[1], "coulomb: a stored state's points start sticking");
  /* inside the cone: |k_t g_T| = 4 <= 0.5 x 30 */
  PetscCall(SetGap(s, 1, 0, -3));
  PetscCall(BoltContactStateAugment(s, &rel, &pen));
  EXPECT(s->lambda[0] == 4 && s->lambda[1] == 0 && s->lambda[2] == -30, "coulomb: stick trial (%g %g %g)", (double)s->lambda[0], (double)s->lambda[1], (double)s->lambda[2]);
  EXPECT(pen == 3, "coulomb: violation %g, not |g.n| = 3", (double)pen);
  PetscCall(BoltContactStateUpdateActive(s, tn, &nchanged, &cycling));
  EXPECT(nchanged == 0 && !s->released[0], "coulomb: sticks inside the cone");
  /* beyond it: the trial 40 returns to the cone, 15 along x; K_c's stiffness across the slip is
     k_t mu |t_N| / |trial| = 1.5 */
  PetscCall(SetGap(s, 10, 0, -3));
  s->lambda[0] = s->lambda[1] = s->lambda[2] = 0; /* (else the normal trial takes the augmented multiplier too) */
  PetscCall(BoltContactStateAugment(s, &rel, &pen));
  EXPECT(s->lambda[0] == 40, "coulomb: stick trial %g", (double)s->lambda[0]);
  PetscCall(BoltContactStateUpdateActive(s, tn, &nchanged, &cycling));
  EXPECT(nchanged == 1 && s->released[0], "coulomb: slips beyond the cone");
  EXPECT(s->lambda[0] == 15 && s->lambda[1] == 0 && s->lambda[2] == -30, "coulomb: return map (%g %g %g)", (double)s->lambda[0], (double)s->lambda[1], (double)s->lambda[2]);
  EXPECT(s->slipDir[0] == 1 && s->slipDir[3] == 1.5, "coulomb: slip direction %g, stiffness across %g", (double)s->slipDir[0], (double)s->slipDir[3]);
  EXPECT(s->frictionChange == 0, "coulomb: convergence measure %g", (double)s->frictionChange);
  BoltContactStatePointCodes(s, codes);
  EXPECT(codes[0] == BOLT_POINT_SLIP && codes[1] == BOLT_POINT_OPEN, "coulomb: point codes %d %d", codes[0], codes[1]);
  /* work 0.5 t.g = 0.5 (15 x 10 + 30 x 3) = 120; slip beyond the stick's, g - t / k_t = (6.25, 0,
     4.5), times the mean tangential traction 7.5: 46.875; stick energy 15^2 / (2 x 4) */
  BoltContactStateEndSolve(s, PETSC_TRUE);
  PetscCall(BoltContactStateContactWork(s, &energy));
  EXPECT(energy == 120, "coulomb: contact work %g", (double)energy);
  PetscCall(BoltContactStateDissipated(s, &energy));
  EXPECT(energy == 46.875, "coulomb: dissipated %g", (double)energy);
  PetscCall(BoltContactStateStickEnergy(s, &energy));
  EXPECT(energy == 28.125, "coulomb: stick energy %g", (double)energy);
  EXPECT(s->anchor[0] == 10 && s->anchor[2] == -3, "coulomb: the next step's stick starts at the raw gap");
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(BoltContactSetDestroy(&c));
  PetscFunctionReturn(0);
}

/* A law of its own, registered from outside: the stick law with its normal penalty doubled and
   every closed point reported sliding. */
static void DoubleTraction(const PetscReal lambda[3], const PetscReal g[3], const PetscReal n[3], PetscReal epsN, PetscReal epsT, PetscReal t[3])
{
  BoltContactLawPenaltyTraction(lambda, g, n, 2 * epsN, epsT, t);
}

static unsigned char AlwaysSlip(const BoltContactState *s, PetscInt gp)
{
  return s->active[gp] ? BOLT_POINT_SLIP : BOLT_POINT_OPEN;
}

static PetscErrorCode CreateDouble(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactLawCreate_Stick(law));
  law->ops.traction  = DoubleTraction;
  law->ops.pointCode = AlwaysSlip;
  law->penaltyFactor = 7;
  PetscFunctionReturn(0);
}

static PetscErrorCode TestRegistered(BoltMesh *m)
{
  BoltContactSet   *c;
  BoltContactState *s;
  BoltContactLaw   *law = NULL;
  PetscReal         rel, pen;
  unsigned char     codes[4];
  PetscErrorCode    ierr;

  PetscFunctionBeginUser;
  PetscCall(BoltContactLawRegisterAll());
  PetscCall(BoltContactLawRegister("double", CreateDouble));
  PetscCall(Scene(m, "double", &c, &s));
  EXPECT(c->law->penaltyFactor == 7, "registered: penalty factor %g", (double)c->law->penaltyFactor);
  PetscCall(SetGap(s, 1, 2, -3));
  PetscCall(BoltContactStateAugment(s, &rel, &pen));
  EXPECT(s->lambda[0] == 4 && s->lambda[1] == 8 && s->lambda[2] == -60, "registered: its traction (%g %g %g)", (double)s->lambda[0], (double)s->lambda[1], (double)s->lambda[2]);
  BoltContactStatePointCodes(s, codes);
  EXPECT(codes[0] == BOLT_POINT_SLIP, "registered: its point code %d", codes[0]);
  PetscCall(BoltContactStateDestroy(&s));
  PetscCall(BoltContactSetDestroy(&c));
  /* an unknown name is refused */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = BoltContactLawCreate(BoltMeshComm(m), "nope", &law);
  PetscCall(PetscPopErrorHandler());
  EXPECT(ierr == PETSC_ERR_USER_INPUT && !law, "registered: an unknown law is refused (%d)", (int)ierr);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  BoltMesh *m;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(BoltMeshCreate(PETSC_COMM_WORLD, &m));
  PetscCall(TestStick(m));
  PetscCall(TestStrict(m));
  PetscCall(TestCoulomb(m));
  PetscCall(TestRegistered(m));
  PetscCall(BoltMeshDestroy(&m));
  printf("%d failures\n", failures);
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
"""


def make_var(name):
    out = subprocess.run(["make", "-s", "--no-print-directory", "--eval", "print-%: ; @echo $($*)", f"print-{name}"],
                         cwd=ROOT, capture_output=True, text=True, check=True)
    return out.stdout.strip()


@pytest.fixture(scope="module")
def program(tmp_path_factory):
    subprocess.run(["make", "-s", "build/libboltrom.a"], cwd=ROOT, check=True, capture_output=True)
    d = tmp_path_factory.mktemp("laws")
    src, exe = d / "laws.c", d / "laws"
    src.write_text(PROGRAM)
    cmd = [make_var("PCC")] + make_var("CFLAGS_B").split() + [str(src), "build/libboltrom.a", "-o", str(exe)] + make_var("LDLIBS_B").split()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return exe


def test_each_law_on_one_point_and_a_law_registered_from_outside(program):
    proc = subprocess.run([str(program)], capture_output=True, text=True, env=ENV, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "0 failures" in proc.stdout

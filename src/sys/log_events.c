/* Every -log_view event and stage of boltrom, registered once. */
#include <sys/resource.h>
#if defined(__GLIBC__)
  #include <malloc.h>
#endif
#include "boltrom.h"

PetscLogEvent BOLT_EVENT_MESH_READ, BOLT_EVENT_MESH_DISTRIBUTE, BOLT_EVENT_ASSEMBLY,
              BOLT_EVENT_CONTACT_SET_UP, BOLT_EVENT_CONTACT_ASSEMBLY, BOLT_EVENT_LOADS,
              BOLT_EVENT_FACTORIZATION, BOLT_EVENT_STATIC_SOLVE, BOLT_EVENT_MODAL_SOLVE,
              BOLT_EVENT_OUTPUT, BOLT_EVENT_CONTACT_STIFFNESS, BOLT_EVENT_DISPLACEMENTS,
              BOLT_EVENT_CONTACT_FORCES, BOLT_EVENT_CONTACT_UPDATE, BOLT_EVENT_BASIS,
              BOLT_EVENT_PROJECTION, BOLT_EVENT_KRYLOV_FACTOR, BOLT_EVENT_KRYLOV_SOLVE,
              BOLT_EVENT_KRYLOV_ORTH, BOLT_EVENT_INTERFACE_REDUCTION, BOLT_EVENT_CONTACT_CHECK;
PetscLogStage BOLT_STAGE_SET_UP, BOLT_STAGE_STATIC, BOLT_STAGE_MODAL, BOLT_STAGE_OUTPUT,
              BOLT_STAGE_PRELOAD, BOLT_STAGE_TRANSIENT;

PetscErrorCode BoltLogRegister(void)
{
  static PetscBool registered = PETSC_FALSE;
  PetscClassId     classid;

  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(0);
  registered = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("boltrom", &classid));
  PetscCall(PetscLogEventRegister("BoltMeshRead", classid, &BOLT_EVENT_MESH_READ));
  PetscCall(PetscLogEventRegister("BoltMeshDistrib", classid, &BOLT_EVENT_MESH_DISTRIBUTE));
  PetscCall(PetscLogEventRegister("BoltAssembly", classid, &BOLT_EVENT_ASSEMBLY));
  PetscCall(PetscLogEventRegister("BoltContactSetUp", classid, &BOLT_EVENT_CONTACT_SET_UP));
  PetscCall(PetscLogEventRegister("BoltContactAsm", classid, &BOLT_EVENT_CONTACT_ASSEMBLY));
  PetscCall(PetscLogEventRegister("BoltLoads", classid, &BOLT_EVENT_LOADS));
  PetscCall(PetscLogEventRegister("BoltFactor", classid, &BOLT_EVENT_FACTORIZATION));
  PetscCall(PetscLogEventRegister("BoltStaticSolve", classid, &BOLT_EVENT_STATIC_SOLVE));
  PetscCall(PetscLogEventRegister("BoltModalSolve", classid, &BOLT_EVENT_MODAL_SOLVE));
  PetscCall(PetscLogEventRegister("BoltOutput", classid, &BOLT_EVENT_OUTPUT));
  PetscCall(PetscLogEventRegister("ContactStiffness", classid, &BOLT_EVENT_CONTACT_STIFFNESS));
  PetscCall(PetscLogEventRegister("Displacements", classid, &BOLT_EVENT_DISPLACEMENTS));
  PetscCall(PetscLogEventRegister("ContactForces", classid, &BOLT_EVENT_CONTACT_FORCES));
  PetscCall(PetscLogEventRegister("ContactUpdate", classid, &BOLT_EVENT_CONTACT_UPDATE));
  PetscCall(PetscLogEventRegister("ContactCheck", classid, &BOLT_EVENT_CONTACT_CHECK));
  PetscCall(PetscLogEventRegister("RomBasis", classid, &BOLT_EVENT_BASIS));
  PetscCall(PetscLogEventRegister("RomProjection", classid, &BOLT_EVENT_PROJECTION));
  PetscCall(PetscLogEventRegister("KrylovFactor", classid, &BOLT_EVENT_KRYLOV_FACTOR));
  PetscCall(PetscLogEventRegister("KrylovSolve", classid, &BOLT_EVENT_KRYLOV_SOLVE));
  PetscCall(PetscLogEventRegister("KrylovOrthog", classid, &BOLT_EVENT_KRYLOV_ORTH));
  PetscCall(PetscLogEventRegister("InterfaceReduce", classid, &BOLT_EVENT_INTERFACE_REDUCTION));
  PetscCall(PetscLogStageRegister("Model set-up", &BOLT_STAGE_SET_UP));
  PetscCall(PetscLogStageRegister("Preload", &BOLT_STAGE_PRELOAD));
  PetscCall(PetscLogStageRegister("Transient", &BOLT_STAGE_TRANSIENT));
  PetscCall(PetscLogStageRegister("Static solve", &BOLT_STAGE_STATIC));
  PetscCall(PetscLogStageRegister("Modal solve", &BOLT_STAGE_MODAL));
  PetscCall(PetscLogStageRegister("Output", &BOLT_STAGE_OUTPUT));
  PetscFunctionReturn(0);
}

/* Resident memory of the largest rank, now and at its peak so far, in GB. Printed after the
   phases that hold FOM-sized factorisations: a big mesh shows where it stands before it runs
   out of memory, not after. */
PetscErrorCode BoltMemoryPrint(MPI_Comm comm, const char phase[])
{
  PetscLogDouble now, mine[2], most[2];
  struct rusage  ru;

  PetscFunctionBeginUser;
  PetscCall(PetscMemoryGetCurrentUsage(&now));
  PetscCheck(getrusage(RUSAGE_SELF, &ru) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS, "getrusage failed");
  mine[0] = now / 1073741824.0;
  mine[1] = PetscMax(now, 1024.0 * (PetscLogDouble)ru.ru_maxrss) / 1073741824.0; /* Linux: kB */
  PetscCall(MPIU_Allreduce(mine, most, 2, MPI_DOUBLE, MPI_MAX, comm));
  PetscCall(PetscPrintf(comm, "Memory after %s: %.2f GB resident, peak %.2f GB (largest rank)\n", phase, most[0], most[1]));
  PetscFunctionReturn(0);
}

/* Hands the heap's free pages back to the system after a FOM-sized structure is destroyed. glibc
   keeps freed memory in its heap for reuse, and the next FOM-sized factorisation does not always
   fit in it: without this a run that has freed its factorisation still counts it as resident. */
PetscErrorCode BoltMemoryRelease(void)
{
  PetscFunctionBeginUser;
#if defined(__GLIBC__)
  (void)malloc_trim(0);
#endif
  PetscFunctionReturn(0);
}

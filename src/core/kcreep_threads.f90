!> How many threads a stage of kcreep runs on.
!>
!> Threads help only where a stage's work is large (docs/performance.md,
!> "Threads"), and only on CPUs that are free: on a busy machine a team of
!> OpenMP threads spins at its barriers while other processes hold the
!> cores, and a run became 10-70 times slower than on one thread. So the
!> automatic count (threads = 0) is, at the start of each stage,
!>   min(CPUs this process may use, CPUs free now, work / work_per_thread)
!> with the CPUs it may use from the affinity mask, the cgroup CPU quota
!> and OpenMP's own limit (OMP_NUM_THREADS, or what the caller set with
!> omp_set_num_threads), and the CPUs free now from the machine's count of
!> runnable threads (less this process's own, which may be pool threads
!> still spinning) and the kcreep solves running on other threads of this
!> process. Under load it is one thread, so no barrier ever waits
!> for a descheduled partner. An explicit count (threads > 0) is used as
!> given. Results do not depend on the count (every parallel sum is taken
!> in a fixed block order).
!>
!> A stage sets its team on the calling thread's OpenMP ICV and restores
!> the caller's value when it ends (enter_team / leave_team), so callers
!> on several threads, each with its own handle, do not disturb each other.
!> A whole run (the command line's case or batch) first enters run_team():
!> every stage then runs on at most that team, and a stage that chose no
!> team of its own runs on it too, never on OpenMP's default count.
module kcreep_threads
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: int64
  !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
  implicit none
  private
  public :: team_size, run_team, enter_team, leave_team, cpus_allowed, serial_blas, solve_started, solve_ended
  public :: cells_per_thread_iterative, cells_per_thread_dense, cells_per_thread_normal, max_threads

  !> Patch cells per thread before a second thread pays, measured on the
  !> 2-core development machine, idle, whole runs, default against one
  !> thread (median of 5 pairs; docs/performance.md "Threads"):
  !> iterative circles of 12,892 / 31,428 / 61,544 cells ran 1.0 / 1.36 /
  !> 1.8 times faster on two threads; dense ones of 1,264 / 2,828 / 5,024
  !> cells 1.0 / 1.24 / 1.65 times, measured with OpenBLAS's threads in the
  !> LU (OpenBLAS is serial now, serial_blas: the dense path's threads run
  !> its assembly and residuals, and 'auto' takes it for small patches only).
  integer, parameter :: cells_per_thread_iterative = 20000
  integer, parameter :: cells_per_thread_dense = 2000
  !> The normal solve's FFT grid (padded, nx ny) per FFTW thread: below it
  !> the threads cost more than they save (docs/performance.md, normal solve).
  integer, parameter :: cells_per_thread_normal = 65000
  !> The largest explicit count accepted (a typo guard, not a machine limit).
  integer, parameter :: max_threads = 1024

  interface
    integer(c_int) function kcreep_affinity_cpus() bind(c)
      import :: c_int
    end function kcreep_affinity_cpus
    integer(c_int) function kcreep_online_cpus() bind(c)
      import :: c_int
    end function kcreep_online_cpus
    integer(c_int) function kcreep_cgroup_cpus() bind(c)
      import :: c_int
    end function kcreep_cgroup_cpus
    integer(c_int) function kcreep_runnable_elsewhere() bind(c)
      import :: c_int
    end function kcreep_runnable_elsewhere
    integer(c_int) function kcreep_solve_started() bind(c)
      import :: c_int
    end function kcreep_solve_started
    subroutine kcreep_solve_ended() bind(c)
    end subroutine kcreep_solve_ended
    integer(c_int) function kcreep_solves_running() bind(c)
      import :: c_int
    end function kcreep_solves_running
    subroutine kcreep_serial_blas() bind(c)
    end subroutine kcreep_serial_blas
  end interface

contains

  !> CPUs this process may use: affinity mask, cgroup quota, OpenMP's limit.
  integer function cpus_allowed() result(n)
    integer :: limit
    n = 1
    !$ n = omp_get_max_threads()
    limit = kcreep_affinity_cpus()
    if (limit > 0) n = min(n, limit)
    limit = kcreep_cgroup_cpus()
    if (limit > 0) n = min(n, limit)
    n = max(n, 1)
  end function cpus_allowed

  !> CPUs free for this solve at this moment: the machine's, less those
  !> running other processes' threads and the other kcreep solves of this
  !> process (callers on other threads).
  integer function cpus_free() result(n)
    integer :: online, elsewhere
    online = kcreep_online_cpus()
    elsewhere = kcreep_runnable_elsewhere()
    if (online < 1 .or. elsewhere < 0) then
      n = huge(1)            ! not known: the allowed count decides
    else
      n = online - elsewhere - max(kcreep_solves_running() - 1, 0)
    end if
  end function cpus_free

  !> A kcreep solve begins (the facade calls this, and solve_ended after).
  subroutine solve_started()
    integer :: running
    running = kcreep_solve_started()
  end subroutine solve_started

  subroutine solve_ended()
    call kcreep_solve_ended()
  end subroutine solve_ended

  !> The team for a stage of `work` cells: `requested` when positive, else
  !> the automatic count described above.
  integer function team_size(requested, work, work_per_thread) result(n)
    integer, intent(in) :: requested
    integer(int64), intent(in) :: work
    integer, intent(in) :: work_per_thread
    if (requested > 0) then
      n = requested
      return
    end if
    if (work / work_per_thread <= 1) then
      ! work for one thread: the same answer without asking the system (cpus_allowed
      ! reads the cgroup's files: 30 us, a tenth of a warm rolling call on 316 cells)
      n = 1
      return
    end if
    n = int(min(int(cpus_allowed(), int64), max(work / work_per_thread, 1_int64)))
    if (n > 1) n = min(n, cpus_free())
    n = max(n, 1)
  end function team_size

  !> The team of a whole run: the CPUs this process may use that are free
  !> now (team_size with no bound from the work). Stages inside choose at
  !> most this many, fewer where their work is small or the load has grown.
  integer function run_team() result(n)
    n = team_size(0, huge(1_int64), 1)
  end function run_team

  !> Run the calling thread's next parallel regions on n threads; previous
  !> receives what leave_team restores.
  subroutine enter_team(n, previous)
    integer, intent(in) :: n
    integer, intent(out) :: previous
    previous = 1
    !$ previous = omp_get_max_threads()
    !$ call omp_set_num_threads(max(n, 1))
  end subroutine enter_team

  subroutine leave_team(previous)
    integer, intent(in) :: previous
    !$ call omp_set_num_threads(max(previous, 1))
  end subroutine leave_team

  !> OpenBLAS on one thread, for good (why: src/core/kcreep_cpus.c).
  subroutine serial_blas()
    call kcreep_serial_blas()
  end subroutine serial_blas

end module kcreep_threads

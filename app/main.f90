!> kcreep: Kalker's creep coefficients of any contact patch (command line).
!> The work is the library's (src/); the command line is app/kcreep_app_cli.
program kcreep_main
  use kcreep_status, only: status_t
  use kcreep, only: serial_blas
  use kcreep_app_cli, only: command_t, parse_command, run_command, stop_with, follow_slurm_cpus
  implicit none
  type(command_t) :: command
  type(status_t) :: status

  call serial_blas()   ! OpenBLAS's pool stopped at once (kcreep's LU runs on one thread)
  call follow_slurm_cpus()
  call parse_command(command, status)
  if (.not. status%failed()) call run_command(command, status)
  if (status%failed()) call stop_with(status)
end program kcreep_main

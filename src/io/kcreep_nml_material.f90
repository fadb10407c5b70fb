!> The &material group: the combined shear modulus and Poisson's ratio.
module kcreep_nml_material
  use, intrinsic :: iso_fortran_env, only: real64
  use kcreep_status, only: status_t, fail, exit_bad_input
  use kcreep_strings, only: rtoa
  use kcreep_limits, only: modulus_in_range
  use kcreep_nml_config, only: config_t, input_where, unset
  implicit none
  private
  public :: material_variables, material_group_t, read_material_group, apply_material_group

  !> The group as written (unset: not given; shape = 'contact' and per-body
  !> moduli in &normal refuse a material written here).
  type :: material_group_t
    real(real64) :: g = unset, nu = unset
  end type material_group_t

  !> The group's variables and their types, as in its namelist statement
  !> (kcreep_namelist_scan diagnose_group explains a failed read with them).
  character(len=*), parameter :: material_variables(2) = [character(len=7) :: &
    'g real', 'nu real']

contains

  subroutine read_material_group(unit, grp, ios, msg)
    integer, intent(in) :: unit
    type(material_group_t), intent(out) :: grp
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    real(real64) :: g, nu
    namelist /material/ g, nu

    g = grp%g
    nu = grp%nu
    read (unit, nml=material, iostat=ios, iomsg=msg)
    grp%g = g
    grp%nu = nu
  end subroutine read_material_group

  !> Check &material and store it in cfg (g = 1, nu = 0.25 when left out).
  subroutine apply_material_group(grp, cfg, status)
    type(material_group_t), intent(in) :: grp
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status

    cfg%material_given = grp%g /= unset .or. grp%nu /= unset
    cfg%g = merge(1.0_real64, grp%g, grp%g == unset)
    cfg%nu = merge(0.25_real64, grp%nu, grp%nu == unset)
    if (.not. modulus_in_range(cfg%g)) call fail(status, exit_bad_input, input_where(cfg)// &
        '&material g = '//rtoa(cfg%g)//' (must be > 0, between 1e-100 and 1e100)')
    if (.not. (cfg%nu >= 0 .and. cfg%nu <= 0.5_real64)) call fail(status, exit_bad_input, input_where(cfg)// &
        '&material nu = '//rtoa(cfg%nu)//' (allowed: 0 <= nu <= 0.5)')
  end subroutine apply_material_group

end module kcreep_nml_material

!> The batch driver counts the failed cases of a partial table it resumes by
!> the verdict column of each row (not the last word: columns follow it), so
!> a resumed batch with an earlier failure still ends with exit status 5.
program test_batch_rows
  use kcreep_table, only: run_record_t, table_row
  use kcreep_app_batch, only: count_error_rows, text_t
  use unit_checks, only: checker_t
  implicit none
  type(checker_t) :: checks
  type(run_record_t) :: failed, solved
  character(len=:), allocatable :: failed_row

  failed%case_name = 'bad'
  failed%scheme = '-'
  failed%method = 'dense'
  failed%verdict = 'error:bad-input'
  solved = failed
  solved%case_name = 'good'
  solved%verdict = 'ok'
  call checks%check(count_error_rows([text_t('# comment'), text_t(table_row(failed)), &
                                      text_t(table_row(solved))]) == 1, 'one error row among two rows')
  call checks%check(count_error_rows([text_t(table_row(solved))]) == 0, 'no error row')
  failed_row = table_row(failed)
  call checks%check(index(failed_row, 'error:') > 0 .and. index(failed_row, 'error:') < len_trim(failed_row) - 30, &
                    'the verdict is not the last word of a row (the case this guards)')
  call checks%finish()
end program test_batch_rows

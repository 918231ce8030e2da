# bash completion for arbor: subcommands, each subcommand's options (read from its own --help, so
# they never go stale), and file names by what each argument takes. Installed as
# share/bash-completion/completions/arbor; or `source tools/arbor-completion.bash`.
_arbor() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} sub="" w exts
  for w in "${COMP_WORDS[@]:1:COMP_CWORD-1}"; do
    case $w in grow|render|compare|merge|export|plan) sub=$w; break ;; esac
  done
  if [ -z "$sub" ]; then
    mapfile -t COMPREPLY < <(compgen -W "grow render compare merge export plan --help --version" -- "$cur")
    return
  fi
  if [[ $cur == -* ]]; then
    local opts
    opts=$("${COMP_WORDS[0]}" "$sub" --help 2>/dev/null | grep -oE -- '--[a-z][a-z-]*' | sort -u)
    mapfile -t COMPREPLY < <(compgen -W "$opts" -- "$cur")
    return
  fi
  case $prev in
    --integrator) mapfile -t COMPREPLY < <(compgen -W "path treemaker" -- "$cur"); return ;;
    --up) mapfile -t COMPREPLY < <(compgen -W "z y" -- "$cur"); return ;;
    -o|--output) exts='exr|png|obj|ply|pbrt|skel' ;;
    --png|--heatmap|--side-by-side) exts='png' ;;
    --seed|--spp|--threads|--width|--height|--time|--quality|--time-limit|--checkpoint-seconds|--passes|--crop|--sky-resolution|--frame|--frames|--tiles|--pass-groups)
      return ;;
    *)
      case $sub in
        grow) exts='toml|xml|lsys|tmpl|skel' ;;
        render|export|plan) exts='toml' ;;
        *) exts='exr|png' ;;
      esac ;;
  esac
  local restore
  restore=$(shopt -p extglob)
  shopt -s extglob
  mapfile -t COMPREPLY < <(compgen -f -X "!*.@($exts)" -- "$cur"; compgen -d -- "$cur")
  eval "$restore"
}
complete -o filenames -F _arbor arbor

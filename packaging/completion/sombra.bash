# bash completion for sombra: its commands, each command's options (read from
# `sombra COMMAND --help`, so they never go stale), the values of the named
# options, and files elsewhere. Installed as
# /usr/share/bash-completion/completions/sombra.
_sombra() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}
    local commands="render explain view merge denoise"
    if ((COMP_CWORD == 1)); then
        COMPREPLY=($(compgen -W "$commands --help --version" -- "$cur"))
        return
    fi
    case $prev in
        --integrator) COMPREPLY=($(compgen -W "direct path" -- "$cur")); return ;;
        --tonemap) COMPREPLY=($(compgen -W "none pbr-neutral" -- "$cur")); return ;;
        --light-tree) COMPREPLY=($(compgen -W "auto on off" -- "$cur")); return ;;
        --texture-filter) COMPREPLY=($(compgen -W "bilinear mipmap" -- "$cur")); return ;;
        --accel) COMPREPLY=($(compgen -W "bvh brute embree" -- "$cur")); return ;;
        --aov) COMPREPLY=($(compgen -W "albedo normal depth position spp variance noisy denoise" -- "$cur")); return ;;
    esac
    if [[ $cur == -* ]]; then
        local options
        options=$("${COMP_WORDS[0]}" "${COMP_WORDS[1]}" --help 2>/dev/null | grep -oE -- '--[a-z][a-z-]*' | sort -u)
        COMPREPLY=($(compgen -W "$options" -- "$cur"))
        return
    fi
    COMPREPLY=($(compgen -f -- "$cur"))
}
complete -o filenames -F _sombra sombra

# Placeholder: replaced by the shader module's embedding (engine/shader).
function(facet_embed_shaders target dir)
endfunction()

import { defineConfig } from 'vite';

// The page is served under /TOKEN/, so every asset URL must be relative.
export default defineConfig({
  base: './',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1500,
  },
});
